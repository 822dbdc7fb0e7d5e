// applyBoundaries on the sparse grid: stored faces of component kTarget that lie on a wall they
// are normal to become 0 (docs/fluid.md; the sparse domain has no periodic axis). In place: each
// invocation writes only its own faces. Twin: fluid/reference/apply_boundaries.cpp.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_common.glsl"

layout(std430, binding = 3) buffer VelocityX {
    float velocityX[];
};
layout(std430, binding = 4) buffer VelocityY {
    float velocityY[];
};
layout(std430, binding = 5) buffer VelocityZ {
    float velocityZ[];
};

void clearWallFace(BrickCell at, int c, ivec3 l) {
    if (!wallNormalFace(c, at.brick * kBrick + l)) return;
    int e = faceElementIn(at.slot, c, l);
    if (c == 0)
        velocityX[e] = 0.0;
    else if (c == 1)
        velocityY[e] = 0.0;
    else
        velocityZ[e] = 0.0;
}

void main() {
    BrickCell at = listedCell();
    int c = int(kTarget);
    // Only a brick on the domain's low or high side along c holds such faces.
    if (at.brick[c] != 0 && at.brick[c] != brickCount()[c] - 1) return;
    clearWallFace(at, c, at.local);
    if (at.local[c] == kBrick - 1) {
        ivec3 top = at.local;
        top[c] = kBrick;
        clearWallFace(at, c, top);
    }
}
