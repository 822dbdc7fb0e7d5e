// updateCgDirection: d = (z - mean) + beta d, or d = z - mean for the first direction (mean and
// beta from finish_reduction; the mean is 0 unless the equation is singular). Twin:
// solvePressureMgpcg in fluid/reference/mgpcg.cpp (Saad 2003, alg. 9.1).
//
// pc: source = z, result = d, flags: MFX_PRESSURE_FIRST.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "pressure_solve_common.glsl"

void main() {
    ivec3 origin;
    if (!levelBrick(0, origin)) return;
    ivec4 cells = levels[0].cells;
    bvec4 inside = insideColumns(cells, origin.x);
    bool first = hasFlag(MFX_PRESSURE_FIRST);
    float mean = scalars.mean;
    float beta = scalars.beta;
    for (int layer = 0; layer < kBrickLayers; ++layer)
        for (int row = 0; row < kBrickRows; ++row) {
            ivec3 q = origin + ivec3(0, row, layer);
            if (q.y >= cells.y || q.z >= cells.z) continue;
            int element = elementIndex(cells, q.x, q.y, q.z);
            // z's mean is over the fluid cells: a solid cell's z (0) stays 0.
            bvec4 fluid = not(solidCells(0, element));
            vec4 d = mix(vec4(0.0), vectors[pc.source + element] - mean,
                         bvec4(uvec4(inside) & uvec4(fluid)));
            if (!first) d += beta * vectors[pc.result + element];
            vectors[pc.result + element] = d;
        }
}
