// The active set's rebuild, 4: every active brick no longer wanted gives its slot back to the free
// stack and leaves the table. One invocation a virtual brick. Twin: SparseBricks::commit (its
// first loop).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_rebuild_common.glsl"

layout(std430, binding = 2) buffer BrickTable {
    uint brickSlot[];
};
layout(std430, binding = 3) readonly buffer Wanted {
    uint wanted[];
};
// Free slots: the count, then the slots (a stack).
layout(std430, binding = 4) buffer FreeSlots {
    int freeCount;
    uint freeSlots[];
};

void main() {
    int index = flatInvocation();
    if (index >= int(rebuild.counts.y)) return;
    uint slot = brickSlot[index];
    if (slot == MFX_NO_SLOT || (wanted[index] & MFX_BRICK_WANTED) != 0u) return;
    freeSlots[atomicAdd(freeCount, 1)] = slot;
    brickSlot[index] = MFX_NO_SLOT;
}
