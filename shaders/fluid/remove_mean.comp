// removeMean: v <- v - mean over the (fluid) cells of level 0, in those cells (when the pressure
// equation is singular, i.e. no face is open: the part of v in the range of A), and the partial
// sums of v², for its norm. Without an open face A's null space is the constants and A p = b is
// solvable only for a mean-free b (docs/fluid.md, "Accuracy options"). Twin:
// consistentRightHandSide in fluid/reference/pressure_equation.cpp.
//
// pc: result = v (in place), flags: MFX_PRESSURE_SUBTRACT_MEAN (PressureScalars.mean, from
// finish_reduction), MFX_PRESSURE_PARTIAL_SUMS.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "pressure_solve_common.glsl"
#include "pressure_partial_sums.glsl"

void main() {
    ivec3 origin;
    float squares = 0.0;
    if (levelBrick(0, origin)) {
        ivec4 cells = levels[0].cells;
        bvec4 inside = insideColumns(cells, origin.x);
        bool subtract = hasFlag(MFX_PRESSURE_SUBTRACT_MEAN);
        float mean = scalars.mean;
        for (int layer = 0; layer < kBrickLayers; ++layer)
            for (int r = 0; r < kBrickRows; ++r) {
                ivec3 q = origin + ivec3(0, r, layer);
                if (q.y >= cells.y || q.z >= cells.z) continue;
                int element = pc.result + elementIndex(cells, q.x, q.y, q.z);
                vec4 v = vectors[element];
                if (subtract) {
                    // The padding and solid cells stay 0.
                    bvec4 fluid = not(solidCells(0, element - pc.result));
                    v = mix(v, v - mean, bvec4(uvec4(inside) & uvec4(fluid)));
                    vectors[element] = v;
                }
                squares += dot(v, v);
            }
    }
    if (hasFlag(MFX_PRESSURE_PARTIAL_SUMS)) writePartialSums(vec4(squares, 0.0, 0.0, 0.0));
}
