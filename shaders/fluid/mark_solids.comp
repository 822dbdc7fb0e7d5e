// markSolids: the sub-step's moving solids put into the grid (docs/fluid.md, "Solids"; Bridson,
// "Fluid Simulation for Computer Graphics", 2nd ed., ch. 5: u·n = u_solid·n on the faces between
// fluid and solid; Crane, Llamas, Tariq, GPU Gems 3 ch. 30: the obstacle voxelised into the grid
// every step with its surface's velocity). Twin: fluid/reference/mark_solids.cpp. Each solid is a
// capsule (shared::FluidSolid) where the step ends, with its two ends' velocities.
//
// With the holders, the solid bits, the flags and the bricks' and blocks' words cleared to 0, the
// passes (kPass, constant id 11); 1, 3 and 4 over the solids' joint bounding box two cells wider
// only (the whole of a periodic axis), from its first cell (dispatchInfo's origin; in words along
// x for passes 1 and 4):
//   0  one workgroup per entry of the box blocks (each solid's bounding box in workgroup-sized
//      blocks; a dispatch per 4,096 entries): each cell of the block whose centre the entry's
//      solid holds takes max(its holder, kMaxSolids - index), so the first solid in list order
//      wins, as in the reference (0 stays air), and its solid bit;
//   1  over the flag words (four cells along x each): the cells' flag bytes
//      (shaders/fluid/fluid_solids.glsl) from the solid bits of the rows around them; a word with
//      any flag marks its Jacobi brick (solve_pressure.comp: 4 x kPressureRows x kPressureLayers
//      cells), so that a sweep reads the flags only where solids are near, and the workgroup
//      blocks that its cells reach (fluid_solids.glsl), so that the other stages read them only
//      there;
//   then, where the stages are split (SolverOptions::solidLists), instead:
//   4  pass 1's flags and the bricks' marks;
//   2  one invocation per block: its word, from the bricks' over its cells (no atomics);
//   5  seven invocations: the block lists (fluid_solids.glsl) and the brick lists
//      (solve_pressure.comp), with their indirect dispatches;
//   and last
//   3  over the box's cells and one more along each axis, or over the blocks near solids (block
//      list 9, kBlockList): every solid face of each component takes its solid's velocity at the
//      face (the solid holding the cell below it, else the one above), and a solid cell's pigment
//      is set to 0.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#include "fluid_solids.glsl"
#include "jacobi_neighbours.glsl"
#include "solid_common.glsl"

// The sub-step's solids (kMaxSolids of room; the first dispatchInfo.target are this step's), and
// pass 0's blocks: entry i is (a solid's index, a workgroup-sized block of the grid its bounding
// box reaches). Uniform buffers: a workgroup reads its entry and solid at one address for all its
// invocations, and a CPU device loads such a value once instead of once an invocation.
layout(std140, binding = 1) uniform Solids {
    FluidSolid solids[1024];
};
layout(std140, binding = 6) uniform SolidBoxBlocks {
    uvec4 boxBlocks[4096];
};
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform writeonly image3D velocityX;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform writeonly image3D velocityY;
layout(binding = 4, MFX_VELOCITY_FORMAT) uniform writeonly image3D velocityZ;
layout(binding = 5, MFX_PIGMENT_FORMAT) uniform writeonly image3D pigment;
// Per cell (x fastest): kMaxSolids - the index of the first solid holding its centre; 0 for air.
layout(std430, binding = 16) buffer SolidHolders {
    uint holders[];
};
// A bit per cell, 32 x-consecutive cells to a word, rows padded to whole words: whether the cell
// is solid (pass 0 sets them, pass 1 reads a row's six bits around a flag word in two loads).
layout(std430, binding = 8) buffer SolidBits {
    uint solidBits[];
};
// The stencils' solid corners (pass 1 writes them; binding 22 is their read-only view).
layout(std430, binding = 9) buffer SolidCornersOut {
    uint cornersOut[];
};
// The flags the stages read (pass 1 writes them; binding 15 is their read-only view).
layout(std430, binding = 17) buffer SolidFlagsOut {
    uint flagsOut[];
};
// One word per Jacobi brick: nonzero where a cell of it has a flag; then the brick lists
// (solve_pressure.comp).
layout(std430, binding = 18) buffer SolidBricks {
    uint solidBricks[];
};
// The block lists (fluid_solids.glsl; binding 21 is a list's uniform window).
layout(std430, binding = 7) buffer SolidListsOut {
    uint listsOut[];
};
// The workgroup blocks' words and the lists' dispatches (fluid_solids.glsl; binding 19 is their
// read-only view).
layout(std430, binding = 20) buffer SolidBlocksOut {
    uint blocksOut[];
};

// Marks the blocks whose cells from one before them to their last include a cell of lo .. hi
// (per axis the blocks lo / S to (hi + 1) / S, S the workgroup's size).
void markBlocks(ivec3 lo, ivec3 hi) {
    uvec3 size = gl_WorkGroupSize;
    uvec3 blocks = (uvec3(cellCount()) + uvec3(1) + size - 1u) / size;
    uvec3 low = uvec3(lo) / size, high = min((uvec3(hi) + 1u) / size, blocks - 1u);
    for (uint k = low.z; k <= high.z; ++k)
        for (uint j = low.y; j <= high.y; ++j)
            for (uint i = low.x; i <= high.x; ++i)
                atomicOr(blocksOut[i + blocks.x * (j + blocks.y * k)], 1u);
}

layout(constant_id = 11) const uint kPass = 0u;
// The Jacobi brick's rows and layers (fluid/smoke_fields.h kPressureRows, kPressureLayers).
const int kBrickRows = 4;
const int kBrickLayers = 4;
// SmokeSolver::kMaxSolids.
const uint kMaxSolids = 1024u;

// The holder of cell q, as the index of its solid + 1; 0 for air.
uint holderOf(ivec3 q) {
    uint h = holders[cellElement(q)];
    return h == 0u ? 0u : kMaxSolids - h + 1u;
}

// The holder of the solid cell beside face q of component c: below first, then above.
uint faceHolder(int c, ivec3 q) {
    ivec3 below = q;
    below[c] -= 1;
    if (below[c] < 0 && periodicAxis(c)) below[c] = cellCount()[c] - 1;
    if (below[c] >= 0) {
        uint holder = holderOf(below);
        if (holder != 0u) return holder;
    }
    ivec3 above = q;
    if (above[c] >= cellCount()[c] && periodicAxis(c)) above[c] = 0;
    return above[c] < cellCount()[c] ? holderOf(above) : 0u;
}

void markFace(int c, ivec3 q) {
    if (wallNormalFace(c, q)) return; // a wall stays a wall
    uint holder = faceHolder(c, q);
    if (holder == 0u) return;
    FluidSolid s = solids[holder - 1u];
    float v = solidVelocityAt(s, facePosition(c, q), c);
    if (c == 0)
        imageStore(velocityX, q, vec4(MFX_STORED(v)));
    else if (c == 1)
        imageStore(velocityY, q, vec4(MFX_STORED(v)));
    else
        imageStore(velocityZ, q, vec4(MFX_STORED(v)));
}

// The solid bits of cells 4 X - 1 .. 4 X + 4 of row (y, z) at bits 0..5 (cells outside the
// grid 0), and, along a periodic x, those of the row's last and first cells.
struct RowBits {
    uint window;
    bool last;
    bool first;
};

int bitWordIndex(int word, int y, int z) {
    return word + ((cellCount().x + 31) / 32) * (y + cellCount().y * z);
}

RowBits rowBits(int X, int y, int z) {
    int n = cellCount().x;
    int low = max(4 * X - 1, 0), high = min(4 * X + 4, n - 1);
    uint w0 = solidBits[bitWordIndex(low >> 5, y, z)];
    uint w1 = solidBits[bitWordIndex(high >> 5, y, z)];
    RowBits r;
    r.window = 0u;
    for (int k = 0; k < 6; ++k) {
        int x = 4 * X - 1 + k;
        uint word = (x >> 5) == (low >> 5) ? w0 : w1;
        if (x >= 0 && x < n && ((word >> uint(x & 31)) & 1u) != 0u) r.window |= 1u << uint(k);
    }
    r.last = false;
    r.first = false;
    if (periodicAxis(0)) {
        r.last = ((solidBits[bitWordIndex((n - 1) >> 5, y, z)] >> uint((n - 1) & 31)) & 1u) != 0u;
        r.first = (solidBits[bitWordIndex(0, y, z)] & 1u) != 0u;
    }
    return r;
}

// Cell 4 X + i of the row (inside the grid).
bool cellBit(RowBits r, int i) {
    return ((r.window >> uint(i + 1)) & 1u) != 0u;
}

// Its -x and +x neighbours as neighbourRef resolves them (none past a non-periodic face), and
// its stencil's +x corner as resolveCell resolves it (clamped: the cell itself).
bool minusXBit(RowBits r, int X, int i) {
    return 4 * X + i > 0 ? ((r.window >> uint(i)) & 1u) != 0u : r.last;
}
bool plusXBit(RowBits r, int X, int i) {
    return 4 * X + i + 1 < cellCount().x ? ((r.window >> uint(i + 2)) & 1u) != 0u : r.first;
}
bool stencilPlusX(RowBits r, int X, int i) {
    bool beyond = 4 * X + i + 1 >= cellCount().x;
    return beyond ? (periodicAxis(0) ? r.first : cellBit(r, i)) : plusXBit(r, X, i);
}

// The flag word of cells 4 X .. 4 X + 3 of row (y, z) (fluid_solids.glsl): each cell's own bit, a
// bit for each side whose neighbour is a solid cell (one inside the grid, or wrapped), and
// whether the stencil q + {0, 1}³ holds a solid; cells past the last are 0. `corners`: the
// cells' stencils' solid corners (fluid_solids.glsl, solidStencilCorners).
uint flagWord(int X, int y, int z, out uint corners) {
    NeighbourRef yMinus = neighbourRef(1, y - 1), yPlus = neighbourRef(1, y + 1);
    NeighbourRef zMinus = neighbourRef(2, z - 1), zPlus = neighbourRef(2, z + 1);
    // The +y and +z rows are also the stencil's (neighbourRef's index resolves as resolveCell).
    RowBits here = rowBits(X, y, z);
    RowBits below = rowBits(X, yMinus.index, z), above = rowBits(X, yPlus.index, z);
    RowBits back = rowBits(X, y, zMinus.index), front = rowBits(X, y, zPlus.index);
    RowBits corner = rowBits(X, yPlus.index, zPlus.index);
    uint word = 0u;
    corners = 0u;
    for (int i = 0; i < 4 && 4 * X + i < cellCount().x; ++i) {
        uint bits = cellBit(here, i) ? 1u : 0u;
        if (minusXBit(here, X, i)) bits |= 2u;
        if (plusXBit(here, X, i)) bits |= 4u;
        if (yMinus.value && cellBit(below, i)) bits |= 8u;
        if (yPlus.value && cellBit(above, i)) bits |= 16u;
        if (zMinus.value && cellBit(back, i)) bits |= 32u;
        if (zPlus.value && cellBit(front, i)) bits |= 64u;
        // Corner k: x from bit 0, the +y row from bit 1, the +z rows from bit 2.
        uint stencil = (cellBit(here, i) ? 1u : 0u) | (stencilPlusX(here, X, i) ? 2u : 0u) |
                       (cellBit(above, i) ? 4u : 0u) | (stencilPlusX(above, X, i) ? 8u : 0u) |
                       (cellBit(front, i) ? 16u : 0u) | (stencilPlusX(front, X, i) ? 32u : 0u) |
                       (cellBit(corner, i) ? 64u : 0u) | (stencilPlusX(corner, X, i) ? 128u : 0u);
        if (stencil != 0u) bits |= 0x80u;
        word |= bits << uint(8 * i);
        corners |= stencil << uint(8 * i);
    }
    return word;
}

// Pass 2, invocation i: the word of block i: whether a flag lies from one cell before the block
// to its last, from the words of the Jacobi bricks over those cells (pass 4's; a brick holding a
// flag outside them makes the block near needlessly, which only costs its stages the tests).
void markNear(uint i) {
    ivec3 n = cellCount();
    uvec3 blocks = solidBlockGrid();
    if (i >= blocks.x * blocks.y * blocks.z) return;
    uvec3 block = uvec3(i % blocks.x, (i / blocks.x) % blocks.y, i / (blocks.x * blocks.y));
    ivec3 first = ivec3(block * gl_WorkGroupSize);
    ivec3 lo = max(first - 1, ivec3(0)), hi = min(first + ivec3(gl_WorkGroupSize) - 1, n - 1);
    ivec3 brickSize = ivec3(4, kBrickRows, kBrickLayers);
    ivec3 bricks = (n + brickSize - 1) / brickSize;
    bool near = false;
    if (all(lessThanEqual(lo, hi)))
        for (int z = lo.z / brickSize.z; z <= hi.z / brickSize.z; ++z)
            for (int y = lo.y / brickSize.y; y <= hi.y / brickSize.y; ++y)
                for (int x = lo.x / brickSize.x; x <= hi.x / brickSize.x; ++x)
                    near = near || solidBricks[x + bricks.x * (y + bricks.y * z)] != 0u;
    blocksOut[i] = near ? 1u : 0u;
}

// Pass 5, invocation `extent` (0 to 4): every block of that extent (the cells, the faces of x, y,
// z, the cells + 1) into its list near solids or away from them, and the two lists' dispatches;
// invocations 5 and 6: every brick near solids, every brick away from them, into their list, and
// its dispatch. (Seven lists built side by side: on a CPU device the seven loops run as one.)
void makeBlockLists(uint extent) {
    uvec3 blocks = solidBlockGrid();
    uint total = blocks.x * blocks.y * blocks.z;
    uvec3 size = uvec3(cellCount()) + (extent == 4u ? uvec3(1u) : uvec3(0u));
    if (extent >= 1u && extent <= 3u) size[extent - 1u] += 1u;
    uint near = 2u * extent, away = near + 1u; // lists L - 1
    uint nearLength = 0u, awayLength = 0u;
    for (uint i = 0u; i < total; ++i) {
        uvec3 block = uvec3(i % blocks.x, (i / blocks.x) % blocks.y, i / (blocks.x * blocks.y));
        if (any(greaterThanEqual(block * gl_WorkGroupSize, size))) continue;
        if (blocksOut[i] != 0u) {
            listsOut[MFX_SOLID_LIST_ENTRIES * near + nearLength] = packSolidBlock(block);
            nearLength += 1u;
        } else {
            listsOut[MFX_SOLID_LIST_ENTRIES * away + awayLength] = packSolidBlock(block);
            awayLength += 1u;
        }
    }
    blocksOut[total + 3u * near] = nearLength;
    blocksOut[total + 3u * away] = awayLength;
}

void makeBrickList(uint list) { // list L - 1: 0 near solids, 1 away from them
    ivec3 bricks = (cellCount() + ivec3(3, kBrickRows - 1, kBrickLayers - 1)) /
                   ivec3(4, kBrickRows, kBrickLayers);
    uint brickCount = uint(bricks.x * bricks.y * bricks.z);
    uint length = 0u;
    for (uint i = 0u; i < brickCount; ++i) {
        if ((solidBricks[i] != 0u) != (list == 0u)) continue;
        uvec3 brick = uvec3(i % uint(bricks.x), (i / uint(bricks.x)) % uint(bricks.y),
                            i / uint(bricks.x * bricks.y));
        solidBricks[brickCount * (list + 1u) + length] = brick.x | (brick.y << 10) | (brick.z << 20);
        length += 1u;
    }
    uint group = gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z;
    solidBricks[3u * brickCount + 3u * list] = (length + group - 1u) / group;
    solidBricks[3u * brickCount + 6u + list] = length;
}

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (kPass == 0u) {
        uvec4 entry = boxBlocks[gl_WorkGroupID.x];
        q = ivec3(entry.yzw * gl_WorkGroupSize + gl_LocalInvocationID);
        if (any(greaterThanEqual(q, cellCount()))) return;
        if (insideSolid(solids[entry.x], cellCentre(q))) {
            atomicMax(holders[cellElement(q)], kMaxSolids - entry.x);
            atomicOr(solidBits[bitWordIndex(q.x >> 5, q.y, q.z)], 1u << uint(q.x & 31));
        }
        return;
    }
    ivec3 n = cellCount();
    if (kPass == 2u) {
        markNear(gl_WorkGroupID.x * (gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z) +
                 gl_LocalInvocationIndex);
        return;
    }
    if (kPass == 5u) {
        uint lane = gl_LocalInvocationIndex;
        if (lane < 5u)
            makeBlockLists(lane);
        else if (lane < 7u)
            makeBrickList(lane - 5u);
        return;
    }
    // Passes 1 and 4 run over the solids' joint box in words along x, pass 3 over its cells, from
    // its origin.
    q += ivec3(dispatchInfo.originX, dispatchInfo.originY, dispatchInfo.originZ);
    if (kPass == 1u || kPass == 4u) {
        int texel = q.x;
        if (4 * texel >= n.x || q.y >= n.y || q.z >= n.z) return;
        uint corners;
        uint word = flagWord(texel, q.y, q.z, corners);
        flagsOut[solidWordIndex(texel, q.y, q.z)] = word;
        cornersOut[solidWordIndex(texel, q.y, q.z)] = corners;
        if (word != 0u) {
            // Pass 1: the blocks its cells reach (markBlocks; the whole word: a block marked near
            // needlessly only reads its flags; pass 2 marks them from the bricks instead); and
            // its brick.
            if (kPass == 1u)
                markBlocks(ivec3(4 * texel, q.y, q.z),
                           ivec3(min(4 * texel + 3, n.x - 1), q.y, q.z));
            ivec3 bricks = (n + ivec3(3, kBrickRows - 1, kBrickLayers - 1)) /
                           ivec3(4, kBrickRows, kBrickLayers);
            int brick = texel + bricks.x * (q.y / kBrickRows + bricks.y * (q.z / kBrickLayers));
            atomicOr(solidBricks[brick], 1u);
        }
        return;
    }
    // Cell q's byte (pass 1's) says whether faces q of the three components are solid: its own
    // bit or its -c neighbour's. Faces past the last cell along an axis look below them.
    if (kBlockList != 0u) q = stageInvocation();
    bool inside = all(lessThan(q, n));
    uint byte = inside ? solidByte(q) : 0xffu;
    if ((byte & 0x2bu) == 0u) return; // bits 0, 1 (-x), 3 (-y), 5 (-z)
    for (int c = 0; c < 3; ++c)
        if (all(lessThan(q, faceCount(c)))) markFace(c, q);
    if (inside && (byte & 1u) != 0u) imageStore(pigment, q, vec4(0.0));
}
