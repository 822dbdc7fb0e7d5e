// storePressure: the solution, packed four cells per vec4 (shaders/shared/pressure_solve.h),
// written one float per cell, x-fastest, into the buffer that SmokeSolver then copies into the
// pressure image (docs/fluid.md, "Grid"); 0 when CG found b = 0. Twin: the pressure the reference
// leaves in fluid/reference/{red_black_gauss_seidel,multigrid,mgpcg}.cpp.
//
// pc: source = x, flags: MFX_PRESSURE_ZERO_IF_NO_RHS.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "pressure_solve_common.glsl"

void main() {
    ivec3 origin;
    if (!levelBrick(0, origin)) return;
    ivec4 cells = levels[0].cells;
    bool zero = hasFlag(MFX_PRESSURE_ZERO_IF_NO_RHS) && scalars.zeroSolution != 0u;
    ivec4 columns = elementColumns(origin.x);
    for (int layer = 0; layer < kBrickLayers; ++layer)
        for (int r = 0; r < kBrickRows; ++r) {
            ivec3 q = origin + ivec3(0, r, layer);
            if (q.y >= cells.y || q.z >= cells.z) continue;
            vec4 x = zero ? vec4(0.0) : vectors[pc.source + elementIndex(cells, q.x, q.y, q.z)];
            int rowStart = cells.x * (q.y + cells.y * q.z);
            for (int c = 0; c < 4; ++c)
                if (columns[c] < cells.x) pressureOut[rowStart + columns[c]] = x[c];
        }
}
