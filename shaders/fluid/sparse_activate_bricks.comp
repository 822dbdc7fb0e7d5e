// Bricks activated this step (the listed ones, marked fresh in the brick states) start as air at rest
// (docs/fluid.md, "Sparse domain"), in two passes (kPass):
//   0: every value of the new bricks' live fields becomes 0;
//   1: each face a new brick shares with a brick that was active before takes that brick's copy
//      (the face was stored and kept its value; only its new copy is new).
// Pass 1 writes only new bricks and reads only bricks active before: no invocation reads what
// another writes.
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
layout(std430, binding = 6) writeonly buffer Pigment {
    vec4 pigment[];
};
layout(std430, binding = 7) writeonly buffer Pressure {
    float pressure[];
};
layout(std430, binding = 8) writeonly buffer Divergence {
    float divergence[];
};

layout(std430, binding = 9) readonly buffer BrickStates {
    uint brickState[];
};

layout(constant_id = 11) const uint kPass = 0u;

float loadFace(int c, int e) {
    return c == 0 ? velocityX[e] : (c == 1 ? velocityY[e] : velocityZ[e]);
}
void storeFace(int c, int e, float v) {
    if (c == 0)
        velocityX[e] = v;
    else if (c == 1)
        velocityY[e] = v;
    else
        velocityZ[e] = v;
}

// Slot of the brick one step from b along c (up or down), if it was active before this step.
uint oldNeighbourSlot(ivec3 b, int c, int step) {
    b[c] += step;
    uint slot = slotOf(b);
    if (slot == MFX_NO_SLOT) return slot;
    ivec3 n = brickCount();
    return (brickState[b.x + n.x * (b.y + n.y * b.z)] & MFX_BRICK_FRESH) != 0u ? MFX_NO_SLOT : slot;
}

void main() {
    BrickCell at = listedCell();
    if (kPass == 0u) {
        int cell = cellElementIn(at.slot, at.local);
        pigment[cell] = vec4(0.0);
        pressure[cell] = 0.0;
        divergence[cell] = 0.0;
        for (int c = 0; c < 3; ++c) {
            storeFace(c, faceElementIn(at.slot, c, at.local), 0.0);
            if (at.local[c] == kBrick - 1) {
                ivec3 top = at.local;
                top[c] = kBrick;
                storeFace(c, faceElementIn(at.slot, c, top), 0.0);
            }
        }
        return;
    }
    for (int c = 0; c < 3; ++c) {
        if (at.local[c] == 0) {
            uint below = oldNeighbourSlot(at.brick, c, -1);
            if (below != MFX_NO_SLOT) {
                ivec3 there = at.local;
                there[c] = kBrick;
                storeFace(c, faceElementIn(at.slot, c, at.local),
                          loadFace(c, faceElementIn(below, c, there)));
            }
        }
        if (at.local[c] == kBrick - 1) {
            uint above = oldNeighbourSlot(at.brick, c, 1);
            if (above != MFX_NO_SLOT) {
                ivec3 here = at.local, there = at.local;
                here[c] = kBrick;
                there[c] = 0;
                storeFace(c, faceElementIn(at.slot, c, here),
                          loadFace(c, faceElementIn(above, c, there)));
            }
        }
    }
}
