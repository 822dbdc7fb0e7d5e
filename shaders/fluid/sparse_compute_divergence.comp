// computeDivergence on the sparse grid: div = (u[i+1]-u[i] + v[j+1]-v[j] + w[k+1]-w[k]) / h for
// every cell of the listed bricks, whose six faces all lie in its own brick (docs/fluid.md).
// Twin: fluid/reference/compute_divergence.cpp with the reference's active cells.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_solids.glsl"

layout(std430, binding = 3) readonly buffer VelocityX {
    float velocityX[];
};
layout(std430, binding = 4) readonly buffer VelocityY {
    float velocityY[];
};
layout(std430, binding = 5) readonly buffer VelocityZ {
    float velocityZ[];
};
layout(std430, binding = 6) writeonly buffer Divergence {
    float divergence[];
};

void main() {
    BrickCell at = listedCell();
    ivec3 l = at.local;
    uint s = at.slot;
    float sum = (velocityX[faceElementIn(s, 0, l + ivec3(1, 0, 0))] - velocityX[faceElementIn(s, 0, l)]) +
                (velocityY[faceElementIn(s, 1, l + ivec3(0, 1, 0))] - velocityY[faceElementIn(s, 1, l)]) +
                (velocityZ[faceElementIn(s, 2, l + ivec3(0, 0, 1))] - velocityZ[faceElementIn(s, 2, l)]);
    int e = cellElementIn(s, l);
    // A solid cell has no pressure unknown, and so no divergence to remove.
    divergence[e] = solidElement(e) ? 0.0 : sum / cellSize();
}
