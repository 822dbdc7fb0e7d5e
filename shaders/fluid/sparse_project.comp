// project on the sparse grid: u -= (p_high - p_low) / h on every stored face of component kTarget
// of the listed bricks that is not on a wall; p = 0 across open sides of the domain and in
// inactive cells (docs/fluid.md, "Sparse domain"); solid faces are left as they are. Twin: fluid/reference/project.cpp with the
// reference's active cells.
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
layout(std430, binding = 6) readonly buffer Pressure {
    float pressure[];
};
layout(std430, binding = 7) writeonly buffer Out {
    float outValues[];
};

float pressureAt(ivec3 q, int axis) {
    if (q[axis] < 0 || q[axis] >= cellCount()[axis]) return 0.0;
    int e = cellElementAt(q);
    return e < 0 ? 0.0 : pressure[e];
}

void projectFace(BrickCell at, int c, ivec3 l) {
    ivec3 q = at.brick * kBrick + l;
    int element = faceElementIn(at.slot, c, l);
    float value = c == 0 ? velocityX[element] : (c == 1 ? velocityY[element] : velocityZ[element]);
    if (!wallNormalFace(c, q) && !sparseSolidFace(c, q)) { // u·n = u_solid·n kept
        ivec3 below = q;
        below[c] -= 1;
        value -= (pressureAt(q, c) - pressureAt(below, c)) * inverseCellSize();
    }
    outValues[element] = value;
}

void main() {
    BrickCell at = listedCell();
    int c = int(kTarget);
    projectFace(at, c, at.local);
    if (at.local[c] == kBrick - 1) {
        ivec3 top = at.local;
        top[c] = kBrick;
        projectFace(at, c, top);
    }
}
