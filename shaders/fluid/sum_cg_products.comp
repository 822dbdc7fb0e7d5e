// sumCgProducts: the partial sums of (r, z), of z and of r, z = M r the preconditioned residual:
// finish_reduction makes z mean-free (when the equation is singular) and (r, z - mean) of them.
// Twin: precondition and dot in solvePressureMgpcg, fluid/reference/mgpcg.cpp.
//
// pc: source = z, rhs = r.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "pressure_solve_common.glsl"
#include "pressure_partial_sums.glsl"

void main() {
    ivec3 origin;
    vec4 sums = vec4(0.0);
    if (levelBrick(0, origin)) {
        ivec4 cells = levels[0].cells;
        for (int layer = 0; layer < kBrickLayers; ++layer)
            for (int row = 0; row < kBrickRows; ++row) {
                ivec3 q = origin + ivec3(0, row, layer);
                if (q.y >= cells.y || q.z >= cells.z) continue;
                int element = elementIndex(cells, q.x, q.y, q.z);
                vec4 z = vectors[pc.source + element];
                vec4 r = vectors[pc.rhs + element];
                sums += vec4(dot(r, z), z.x + z.y + z.z + z.w, r.x + r.y + r.z + r.w, 0.0);
            }
    }
    writePartialSums(sums);
}
