// Moving solids in the grid (docs/fluid.md, "Solids"), as the stages read them: the solid cells
// of the sub-step, marked by shaders/fluid/mark_solids.comp into one flag byte per cell, four
// x-consecutive cells to a word, rows padded to whole words (word X + ceil(nx / 4) (y + ny z) holds
// cells 4X..4X+3 of row (y, z), the layout of the Jacobi sweep's packed pressure):
//   bit 0     the cell is solid (its centre inside a capsule)
//   bit 1 + s the cell's neighbour on side s (-x, +x, -y, +y, -z, +z) is a solid cell (a
//             neighbour inside the grid, or across a periodic face)
//   bit 7     one of the eight cells q + {0, 1}³ (each resolved as a fetch resolves it, clamped or
//             wrapped) is solid: a trilinear sample whose stencil starts at q touches a solid
//             (which of the eight: solidStencilCorners)
// so that a row of four cells is one load, and whether a face is solid is one byte. Twin:
// fluid/reference/mark_solids.cpp. Without solids (kSolids false, constant id 15) every test below
// folds to false and a stage is the one it was before solids existed.
#ifndef MFX_FLUID_SOLIDS_GLSL
#define MFX_FLUID_SOLIDS_GLSL

layout(constant_id = 15) const bool kSolids = false;

layout(std430, binding = 15) readonly buffer SolidFlags {
    uint solidFlags[];
};
// The trilinear stencil whose low corner is a cell: one byte per cell in the flags' layout, bit k
// set where corner k (cell + (k & 1, (k >> 1) & 1, k >> 2), resolved as a fetch resolves it) is a
// solid cell (mark_solids.comp writes them), so that a sample knows its solid corners from one
// load.
layout(std430, binding = 22) readonly buffer SolidCorners {
    uint solidCorners[];
};

// The solids' block words (mark_solids.comp writes them):
//   [0, T)            one word per block of the workgroup's shape over cells + 1 along each axis
//                     (T blocks): nonzero where a cell from one before the block to its last has
//                     a nonzero flag byte, so that a workgroup of a dispatch over the cells or
//                     faces from 0 knows from one load, the same for all its invocations,
//                     whether any solid test of its own cells and faces can be true;
//   [T + 3 (L - 1), + 3)  block list L's indirect dispatch (its length, 1, 1).
layout(std430, binding = 19) readonly buffer SolidBlocks {
    uint solidBlocks[];
};
// Block list L (1 to kSolidBlockLists), bound as the window of 4 kSolidListEntries words at
// L - 1 of them: the blocks near solids (odd L) or away from them (even L) among those a
// dispatch over extent (L - 1) / 2 covers (0 the cells, 1 to 3 the faces of x, y, z, 4 the
// cells + 1), packed (packSolidBlock). A uniform buffer: a workgroup reads its entry at one
// address for all its invocations, and a CPU device loads such a value once, not once an
// invocation.
layout(std140, binding = 21) uniform SolidBlockList {
    uvec4 solidBlockList[MFX_SOLID_LIST_ENTRIES / 4u];
};
const uint kSolidBlockLists = MFX_SOLID_BLOCK_LISTS;

// Which list a dispatch's workgroups walk (constant id 16): 0 none (workgroup g is block g),
// else block list L above: a stage dispatched twice, once over the blocks away from solids, where
// every solid test gated by solidsNearWorkgroup() compiles out, and once over those near them.
layout(constant_id = 16) const uint kBlockList = 0u;

uvec3 solidBlockGrid() {
    return (uvec3(cellCount()) + uvec3(1) + gl_WorkGroupSize - 1u) / gl_WorkGroupSize;
}

// The block index of workgroup g (mark_solids.comp writes them).
int solidBlockIndex(uvec3 g) {
    uvec3 blocks = solidBlockGrid();
    return int(g.x + blocks.x * (g.y + blocks.y * g.z));
}

// A list's entry: the block's coordinates, x + 2048 y + 2048² z (SmokeSolver splits a stage only
// where the blocks along x and y number at most 2048 and along z at most 1024), so that a
// workgroup finds its block without a division.
uint packSolidBlock(uvec3 block) {
    return block.x | (block.y << 11) | (block.z << 22);
}
uvec3 unpackSolidBlock(uint entry) {
    return uvec3(entry & 0x7ffu, (entry >> 11) & 0x7ffu, entry >> 22);
}

// The block this workgroup computes: its own, or its entry in the block list it walks.
uvec3 stageWorkGroup() {
    if (kBlockList == 0u) return gl_WorkGroupID;
    uint i = gl_WorkGroupID.x;
    return unpackSolidBlock(solidBlockList[i >> 2u][i & 3u]);
}

// The cell or face this invocation computes (gl_GlobalInvocationID without a block list).
ivec3 stageInvocation() {
    return ivec3(stageWorkGroup() * gl_WorkGroupSize + gl_LocalInvocationID);
}

// Whether this workgroup's cells and faces (a dispatch from cell or face 0 in the solver's
// workgroup shape) may have solids: where false, solidCell, solidFace and solidNeighbours of them
// are all false. Walking a block list it is known without a load.
bool solidsNearWorkgroup() {
    if (!kSolids) return false;
    if (kBlockList != 0u) return kBlockList % 2u == 1u;
    return solidBlocks[solidBlockIndex(gl_WorkGroupID)] != 0u;
}

// The word of cells 4 texel .. 4 texel + 3 of row (y, z).
int solidWordIndex(int texel, int y, int z) {
    return texel + ((cellCount().x + 3) / 4) * (y + cellCount().y * z);
}

// The flag byte of cell q (inside the grid); 0 without solids.
uint solidByte(ivec3 q) {
    if (!kSolids) return 0u;
    return (solidFlags[solidWordIndex(q.x >> 2, q.y, q.z)] >> (8 * (q.x & 3))) & 0xffu;
}

// Whether cell q (inside the grid) is solid.
bool solidCell(ivec3 q) {
    return (solidByte(q) & 1u) != 0u;
}

// The solid corners of the trilinear stencil whose low corner is cell i0 (resolved as a fetch
// resolves it), corner k at bit k; 0 without solids.
uint solidStencilCorners(ivec3 i0) {
    if (!kSolids) return 0u;
    ivec3 q = resolveCell(i0);
    uint corners = (solidCorners[solidWordIndex(q.x >> 2, q.y, q.z)] >> (8 * (q.x & 3))) & 0xffu;
    // Below cell 0 of a clamped axis both of the stencil's cells along it are cell 0, whose byte
    // has cells 0 and 1: its low corners stand for the high ones too.
    const uint low[3] = uint[3](0x55u, 0x33u, 0x0fu);
    for (int a = 0; a < 3; ++a)
        if (!periodicAxis(a) && i0[a] < 0) corners = (corners & low[a]) | ((corners & low[a]) << (1u << uint(a)));
    return corners;
}

// solidStencilCorners in a stage: walking the blocks away from solids, none where the stencil
// starts from one cell before this workgroup's block to its last (the mark left every flag byte
// there 0, stencil bit included: mark_solids.comp), without a load; else from the corner bytes.
uint stageStencilCorners(ivec3 i0) {
    if (kBlockList != 0u && kBlockList % 2u == 0u) {
        // Cells inside the grid only: a stencil from past a periodic face wraps to cells the
        // block's flags do not cover.
        ivec3 first = ivec3(stageWorkGroup() * gl_WorkGroupSize);
        if (all(greaterThanEqual(i0, max(first - 1, ivec3(0)))) &&
            all(lessThan(i0, min(first + ivec3(gl_WorkGroupSize), cellCount()))))
            return 0u;
    }
    return solidStencilCorners(i0);
}

// The six sides' solid-neighbour bits of cell q (inside the grid), side s at bit s.
uint solidNeighbours(ivec3 q) {
    return (solidByte(q) >> 1) & 63u;
}

// Whether face q of component c is solid: a cell beside it is (cells beyond a non-periodic face
// are not), and it is not wall-normal (a wall stays a wall). One byte: cell q's own bit and its
// -c neighbour's, or past the last cell, cell q - e_c's own bit and its +c neighbour's.
bool solidFace(int c, ivec3 q) {
    if (!kSolids || wallNormalFace(c, q)) return false;
    ivec3 cell = q;
    uint side = uint(2 * c);
    if (q[c] >= cellCount()[c]) {
        cell[c] -= 1;
        side += 1u;
    }
    return (solidByte(cell) & (1u | (2u << side))) != 0u;
}

#endif
