// solvePressure on the sparse grid, one Jacobi sweep over the cells of the listed bricks:
//   p <- (sum of counted neighbour pressures - h² div) / count
// as the dense solve (docs/fluid.md, step 10): a neighbour across a wall is not counted, one across
// an open side of the domain is counted with p = 0, and so is an inactive neighbour inside the
// domain (docs/fluid.md, "Sparse domain": open air at p = 0); a solid neighbour is not counted
// and a solid cell holds p = 0 (docs/fluid.md, "Solids"). Twin:
// fluid/reference/solve_pressure.cpp (solvePressureJacobi) with the reference's active cells.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_solids.glsl"

layout(std430, binding = 3) readonly buffer Divergence {
    float divergence[];
};
layout(std430, binding = 4) readonly buffer PressureIn {
    float pressureIn[];
};
layout(std430, binding = 5) writeonly buffer PressureOut {
    float pressureOut[];
};

void main() {
    BrickCell at = listedCell();
    ivec3 q = at.brick * kBrick + at.local;
    ivec3 n = cellCount();
    float sum = 0.0;
    float count = 0.0;
    for (int s = 0; s < 6; ++s) {
        int axis = s >> 1;
        bool high = (s & 1) != 0;
        ivec3 step = ivec3(0);
        step[axis] = high ? 1 : -1;
        ivec3 neighbour = q + step;
        if (neighbour[axis] >= 0 && neighbour[axis] < n[axis]) {
            int e = nearbyCellElement(at, at.local + step, neighbour);
            if (solidElement(e)) continue; // zero normal gradient, as at a wall
            sum += e < 0 ? 0.0 : pressureIn[e];
            count += 1.0;
        } else if (boundaryKind(axis, high) == MFX_BOUNDARY_OPEN) {
            count += 1.0; // ghost pressure 0
        }
    }
    int element = cellElementIn(at.slot, at.local);
    float h = cellSize();
    // No unknown inside a solid: p = 0.
    pressureOut[element] = count > 0.0 && !solidElement(element)
                               ? (sum - h * h * divergence[element]) / count
                               : 0.0;
}
