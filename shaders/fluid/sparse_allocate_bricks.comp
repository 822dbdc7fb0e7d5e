// The active set's rebuild, 5: every wanted brick without a slot takes one from the free stack
// (marked fresh: its values start at rest), or is refused and counted when the stack is empty;
// every brick with a slot is appended to the active list, every fresh one to the activated list
// (in no particular order: the stages' results do not depend on it). One invocation a virtual
// brick. Twin: SparseBricks::commit (its second loop; it hands out the lowest slots first, this
// pass any free one).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_rebuild_common.glsl"

layout(std430, binding = 2) buffer BrickTable {
    uint brickSlot[];
};
layout(std430, binding = 3) buffer Wanted {
    uint wanted[];
};
layout(std430, binding = 4) buffer FreeSlots {
    int freeCount;
    uint freeSlots[];
};
layout(std430, binding = 5) buffer ActiveList {
    BrickListHeader activeHeader;
    uint activeBricks[];
};
layout(std430, binding = 6) buffer ActivatedList {
    BrickListHeader activatedHeader;
    uint activatedBricks[];
};
layout(std430, binding = 7) buffer Refused {
    uint refused;
};

void main() {
    int index = flatInvocation();
    if (index >= int(rebuild.counts.y)) return;
    if ((wanted[index] & MFX_BRICK_WANTED) == 0u) return;
    uint slot = brickSlot[index];
    if (slot == MFX_NO_SLOT) {
        // Nothing is pushed during this pass, so once the stack is empty it stays empty: a pop
        // that finds it empty undoes its decrement and is refused.
        int top = atomicAdd(freeCount, -1);
        if (top <= 0) {
            atomicAdd(freeCount, 1);
            atomicAdd(refused, 1u);
            return;
        }
        slot = freeSlots[top - 1];
        brickSlot[index] = slot;
        wanted[index] = MFX_BRICK_WANTED | MFX_BRICK_FRESH;
        uint entry = atomicAdd(activatedHeader.count, 1u);
        atomicAdd(activatedHeader.groupsX, 2u);
        activatedBricks[entry] = uint(index);
    }
    uint entry = atomicAdd(activeHeader.count, 1u);
    atomicAdd(activeHeader.groupsX, 2u);
    activeBricks[entry] = uint(index);
}
