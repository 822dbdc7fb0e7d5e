// updateCgSolution: p += alpha d, r -= alpha q (alpha from finish_reduction), and the partial sums
// of (r, r) for the stopping test. Twin: the update in solvePressureMgpcg,
// fluid/reference/mgpcg.cpp (Saad 2003, alg. 9.1).
//
// pc: result = p, source = d, rhs = r, other = q.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "pressure_solve_common.glsl"
#include "pressure_partial_sums.glsl"

void main() {
    ivec3 origin;
    float rr = 0.0;
    if (levelBrick(0, origin)) {
        ivec4 cells = levels[0].cells;
        float alpha = scalars.alpha;
        for (int layer = 0; layer < kBrickLayers; ++layer)
            for (int row = 0; row < kBrickRows; ++row) {
                ivec3 q = origin + ivec3(0, row, layer);
                if (q.y >= cells.y || q.z >= cells.z) continue;
                int element = elementIndex(cells, q.x, q.y, q.z);
                vectors[pc.result + element] += alpha * vectors[pc.source + element];
                vec4 r = vectors[pc.rhs + element] - alpha * vectors[pc.other + element];
                vectors[pc.rhs + element] = r;
                rr += dot(r, r);
            }
    }
    writePartialSums(vec4(rr, 0.0, 0.0, 0.0));
}
