// Grid access of the sparse smoke grid (shaders/shared/sparse_fluid.h): which brick and cell an
// invocation works on, and where a face or cell of the virtual domain is stored, if anywhere.
// Everything else (boundary rules, positions, sampling) is the dense grid's, fluid_common.glsl,
// over the virtual domain: a value that is not stored reads as 0, air at rest without pigment
// (docs/fluid.md, "Sparse domain"). Twin: fluid/reference/sparse_reference_solver.cpp.
#ifndef MFX_SPARSE_COMMON_GLSL
#define MFX_SPARSE_COMMON_GLSL

#include "fluid_common.glsl"
#include "shared/sparse_fluid.h"

layout(std430, binding = 1) readonly buffer BrickTable {
    uint brickSlot[];
};
// The bricks this dispatch runs over: every active brick, or those activated this step.
layout(std430, binding = 2) readonly buffer BrickList {
    BrickListHeader listHeader;
    uint listedBricks[];
};

const int kBrick = int(MFX_BRICK_SIZE);

ivec3 brickCount() {
    return cellCount() / kBrick;
}

// The atlas slot of brick b, or MFX_NO_SLOT (inactive, or outside the domain).
uint slotOf(ivec3 b) {
    ivec3 n = brickCount();
    if (any(lessThan(b, ivec3(0))) || any(greaterThanEqual(b, n))) return MFX_NO_SLOT;
    return brickSlot[b.x + n.x * (b.y + n.y * b.z)];
}

// The listed brick of this workgroup (two workgroups of 8x8x4 a brick), its slot, and the
// invocation's cell in it.
struct BrickCell {
    ivec3 brick;
    uint slot;
    ivec3 local; // 0..7 each
};

BrickCell listedCell() {
    uint index = listedBricks[gl_WorkGroupID.x >> 1];
    ivec3 n = brickCount();
    BrickCell at;
    at.brick = ivec3(int(index) % n.x, (int(index) / n.x) % n.y, int(index) / (n.x * n.y));
    at.slot = brickSlot[index];
    at.local = ivec3(gl_LocalInvocationID) + ivec3(0, 0, 4 * int(gl_WorkGroupID.x & 1u));
    return at;
}

int brickCellIndex(ivec3 l) {
    return l.x + kBrick * (l.y + kBrick * l.z);
}
// Brick-local index of face l of component c (l[c] in 0..8).
int brickFaceIndex(int c, ivec3 l) {
    ivec3 e = ivec3(kBrick);
    e[c] = kBrick + 1;
    return l.x + e.x * (l.y + e.y * l.z);
}
int cellElementIn(uint slot, ivec3 l) {
    return int(slot * MFX_BRICK_CELLS) + brickCellIndex(l);
}
int faceElementIn(uint slot, int c, ivec3 l) {
    return int(slot * MFX_BRICK_FACES) + brickFaceIndex(c, l);
}

// Where cell q (inside the domain) is stored, or -1.
int cellElementAt(ivec3 q) {
    ivec3 b = q >> 3;
    uint slot = slotOf(b);
    return slot == MFX_NO_SLOT ? -1 : cellElementIn(slot, q - b * kBrick);
}

// Where the cell at brick-local position l of `at`'s brick is stored, l one step from the
// invocation's cell: in its own slot while l stays in the brick (no table lookup), else as
// cellElementAt (q: the cell in the domain).
int nearbyCellElement(BrickCell at, ivec3 l, ivec3 q) {
    if (all(greaterThanEqual(l, ivec3(0))) && all(lessThan(l, ivec3(kBrick))))
        return cellElementIn(at.slot, l);
    return cellElementAt(q);
}

// Where face q of component c (0 <= q[c] <= n[c]) is stored, or -1: in the brick of the cell
// above it along c, else as layer 8 of the brick below.
int faceElementAt(int c, ivec3 q) {
    ivec3 b = q >> 3;
    uint slot = slotOf(b);
    if (slot == MFX_NO_SLOT) {
        if ((q[c] & (kBrick - 1)) != 0) return -1;
        b[c] -= 1;
        slot = slotOf(b);
        if (slot == MFX_NO_SLOT) return -1;
    }
    return faceElementIn(slot, c, q - b * kBrick);
}

#endif
