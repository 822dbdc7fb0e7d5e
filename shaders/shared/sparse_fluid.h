// Layout of the sparse smoke grid (fluid/sparse_smoke_solver.h, docs/fluid.md "Sparse domain"),
// shared by its compute shaders and C++.
//
// The virtual domain is cut into bricks of MFX_BRICK_SIZE^3 cells. The brick table holds, per
// virtual brick (x fastest), its slot in the atlas or MFX_NO_SLOT. In the atlas, slot s holds
//   a cell field (pigment, pressure, divergence): elements s * MFX_BRICK_CELLS + l.x + 8 (l.y + 8
//   l.z) velocity component c: elements s * MFX_BRICK_FACES + its brick-local face index, the faces
//     of the brick's cells on both sides: 9 layers along axis c, 8 along the other two.
// A face between two active bricks is therefore stored twice (layer 8 of the lower brick, layer 0
// of the upper one); every stage computes both copies from the same inputs with the same code, so
// they hold the same value.
#ifndef MFX_SHARED_SPARSE_FLUID_H
#define MFX_SHARED_SPARSE_FLUID_H

#include "common.h"

#define MFX_BRICK_SIZE 8u
#define MFX_BRICK_CELLS 512u
#define MFX_BRICK_FACES 576u
#define MFX_NO_SLOT 0xffffffffu

MFX_SHARED_BEGIN

// Head of a list of bricks (the active ones, or those activated this step): a
// VkDispatchIndirectCommand of two workgroups of 8x8x4 a brick, then the number of bricks; the
// brick indices follow as uints.
struct BrickListHeader {
    uint groupsX;
    uint groupsY;
    uint groupsZ;
    uint count;
};

// Per virtual brick, in the brick state buffer: wanted in the step being built, and activated by
// it (its values start at rest).
#define MFX_BRICK_WANTED 1u
#define MFX_BRICK_FRESH 2u

// Uniform of the active set's rebuild on the GPU (shaders/fluid/sparse_*_bricks.comp).
struct SparseRebuildParameters {
    vec4 thresholds; // x: pigment alpha, y: cell-centre speed above which a cell is live
    uvec4 counts;    // x: the dilation's reach in bricks, y: virtual bricks, z: atlas slots
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(BrickListHeader, 16);
MFX_CHECK_LAYOUT(BrickListHeader, count, 12);
MFX_CHECK_SIZE(SparseRebuildParameters, 32);
MFX_CHECK_LAYOUT(SparseRebuildParameters, counts, 16);
#endif

#endif
