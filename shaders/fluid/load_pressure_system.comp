// loadPressureSystem: the right-hand side b = -h² div of the pressure equation A p = b and the
// starting pressure (the last step's with a warm start, else 0), packed four cells per vec4 into
// level 0's vectors (shaders/shared/pressure_solve.h); optionally the partial sums of b, for its
// mean, with the cells it is over (the fluid ones, with solids: a solid cell's b and x are 0).
// Twin: the set-up of solvePressureRedBlack / solvePressureMultigrid / solvePressureMgpcg in
// fluid/reference/ (docs/fluid.md, "Accuracy options").
//
// pc: result = x, rhs = b, scale = -h², flags: MFX_PRESSURE_WARM_START, MFX_PRESSURE_PARTIAL_SUMS
// (x: sum b, y: the cells counted).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "pressure_solve_common.glsl"
#include "pressure_partial_sums.glsl"

void main() {
    ivec3 origin;
    float sum = 0.0, fluidCells = 0.0;
    if (levelBrick(0, origin)) {
        ivec4 cells = levels[0].cells;
        ivec4 columns = elementColumns(origin.x);
        bvec4 inside = insideColumns(cells, origin.x);
        for (int layer = 0; layer < kBrickLayers; ++layer)
            for (int r = 0; r < kBrickRows; ++r) {
                ivec3 q = origin + ivec3(0, r, layer);
                if (q.y >= cells.y || q.z >= cells.z) continue;
                vec4 b = vec4(0.0), x = vec4(0.0);
                for (int c = 0; c < 4; ++c) {
                    if (!inside[c]) continue;
                    ivec3 cell = ivec3(columns[c], q.y, q.z);
                    b[c] = pc.scale * imageLoad(divergence, cell).r;
                    if (hasFlag(MFX_PRESSURE_WARM_START)) x[c] = imageLoad(pressure, cell).r;
                }
                int element = elementIndex(cells, q.x, q.y, q.z);
                // No unknown in a solid cell: b and x 0 there, and the cells counted for the
                // mean are the fluid ones.
                bvec4 solid = solidCells(0, element);
                b = mix(b, vec4(0.0), solid);
                x = mix(x, vec4(0.0), solid);
                vectors[pc.rhs + element] = b;
                vectors[pc.result + element] = x;
                sum += b.x + b.y + b.z + b.w;
                vec4 counted = mix(vec4(inside), vec4(0.0), solid);
                fluidCells += counted.x + counted.y + counted.z + counted.w;
            }
    }
    if (hasFlag(MFX_PRESSURE_PARTIAL_SUMS)) writePartialSums(vec4(sum, fluidCells, 0.0, 0.0));
}
