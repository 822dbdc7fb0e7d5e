// markSolids: the sub-step's moving solids put into the grid (docs/fluid.md, "Solids"; Bridson,
// "Fluid Simulation for Computer Graphics", 2nd ed., ch. 5: u·n = u_solid·n on the faces between
// fluid and solid; Crane, Llamas, Tariq, GPU Gems 3 ch. 30: the obstacle voxelised into the grid
// every step with its surface's velocity). Twin: fluid/reference/mark_solids.cpp. Each solid is a
// capsule (shared::FluidSolid) where the step ends, with its two ends' velocities.
//
// With the holders, the flags and the bricks' and blocks' words cleared to 0, three passes (kPass,
// constant id 11), 1 and 2 over the solids' joint bounding box two cells wider only (the whole
// of a periodic axis), from its first cell (dispatchInfo's origin; in words along x for pass 1):
//   0  one dispatch per solid over the cells of its bounding box (the solid's index in
//      dispatchInfo.target, the box's first cell in its origin): each cell whose centre it holds
//      takes max(its holder, kMaxSolids - index), so the first solid in list order wins, as in the
//      reference; 0 stays air;
//   1  over the flag words (four cells along x each): the cells' flag bytes
//      (shaders/fluid/fluid_solids.glsl); a word with any flag marks its Jacobi brick
//      (solve_pressure.comp: 4 x kPressureRows x kPressureLayers cells), so that a sweep reads the
//      flags only where solids are near, and a cell with a flag the workgroup blocks that reach it
//      (fluid_solids.glsl), so that the other stages read them only there;
//   2  over the box's cells and one more along each axis: every solid face of each component takes its solid's
//      velocity at the face (the solid holding the cell below it, else the one above), and a solid
//      cell's pigment is set to 0.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#include "fluid_solids.glsl"
#include "jacobi_neighbours.glsl"

// The sub-step's solids, bound with exactly their count's range.
layout(std430, binding = 1) readonly buffer Solids {
    FluidSolid solids[];
};
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform writeonly image3D velocityX;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform writeonly image3D velocityY;
layout(binding = 4, MFX_VELOCITY_FORMAT) uniform writeonly image3D velocityZ;
layout(binding = 5, MFX_PIGMENT_FORMAT) uniform writeonly image3D pigment;
// Per cell (x fastest): kMaxSolids - the index of the first solid holding its centre; 0 for air.
layout(std430, binding = 16) buffer SolidHolders {
    uint holders[];
};
// The flags the stages read (pass 1 writes them; binding 15 is their read-only view).
layout(std430, binding = 17) buffer SolidFlagsOut {
    uint flagsOut[];
};
// One word per Jacobi brick: nonzero where a cell of it has a flag.
layout(std430, binding = 18) buffer SolidBricks {
    uint solidBricks[];
};
// The workgroup blocks' words (fluid_solids.glsl; binding 19 is their read-only view).
layout(std430, binding = 20) buffer SolidBlocksOut {
    uint blocksOut[];
};

// Marks the blocks whose cells from one before them to their last include cell x (per axis the
// blocks x / S and (x + 1) / S, S the workgroup's size).
void markBlocks(ivec3 x) {
    uvec3 size = gl_WorkGroupSize;
    uvec3 blocks = (uvec3(cellCount()) + uvec3(1) + size - 1u) / size;
    uvec3 low = uvec3(x) / size, high = min((uvec3(x) + 1u) / size, blocks - 1u);
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

// Where the point of the axis closest to x lies along it: 0 at end A, 1 at end B.
float axisParameter(FluidSolid s, vec3 x) {
    vec3 ab = s.endB.xyz - s.endA.xyz;
    float length2 = dot(ab, ab);
    return length2 > 0.0 ? clamp(dot(x - s.endA.xyz, ab) / length2, 0.0, 1.0) : 0.0;
}

bool insideSolid(FluidSolid s, vec3 x) {
    vec3 closest = mix(s.endA.xyz, s.endB.xyz, axisParameter(s, x));
    vec3 d = x - closest;
    return dot(d, d) < s.endA.w * s.endA.w;
}

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
    float v = mix(s.velocityA.xyz, s.velocityB.xyz, axisParameter(s, facePosition(c, q)))[c];
    if (c == 0)
        imageStore(velocityX, q, vec4(MFX_STORED(v)));
    else if (c == 1)
        imageStore(velocityY, q, vec4(MFX_STORED(v)));
    else
        imageStore(velocityZ, q, vec4(MFX_STORED(v)));
}

// Cell q's flag byte: its own bit, a bit for each side whose neighbour is a solid cell (one
// inside the grid, or wrapped), and whether the stencil q + {0, 1}³ holds a solid.
uint flagByte(ivec3 q) {
    uint bits = holders[cellElement(q)] != 0u ? 1u : 0u;
    for (int side = 0; side < 6; ++side) {
        int axis = side / 2;
        NeighbourRef ref = neighbourRef(axis, q[axis] + ((side & 1) == 0 ? -1 : 1));
        ivec3 neighbour = q;
        neighbour[axis] = ref.index;
        if (ref.value && holders[cellElement(neighbour)] != 0u) bits |= 2u << uint(side);
    }
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 cell = resolveCell(q + ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1));
        if (holders[cellElement(cell)] != 0u) bits |= 0x80u;
    }
    return bits;
}

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (kPass == 0u) {
        q += ivec3(dispatchInfo.originX, dispatchInfo.originY, dispatchInfo.originZ);
        if (any(greaterThanEqual(q, cellCount()))) return;
        uint index = dispatchInfo.target;
        if (insideSolid(solids[index], cellCentre(q)))
            atomicMax(holders[cellElement(q)], kMaxSolids - index);
        return;
    }
    ivec3 n = cellCount();
    // Passes 1 and 2 run over the solids' joint box (in words along x for pass 1), from its origin.
    q += ivec3(dispatchInfo.originX, dispatchInfo.originY, dispatchInfo.originZ);
    if (kPass == 1u) {
        int texel = q.x;
        if (4 * texel >= n.x || q.y >= n.y || q.z >= n.z) return;
        uint word = 0u;
        for (int i = 0; i < 4 && 4 * texel + i < n.x; ++i) {
            uint byte = flagByte(ivec3(4 * texel + i, q.y, q.z));
            word |= byte << (8 * i);
            if (byte != 0u) markBlocks(ivec3(4 * texel + i, q.y, q.z));
        }
        flagsOut[solidWordIndex(texel, q.y, q.z)] = word;
        if (word != 0u) {
            ivec3 bricks = (n + ivec3(3, kBrickRows - 1, kBrickLayers - 1)) /
                           ivec3(4, kBrickRows, kBrickLayers);
            int brick = texel + bricks.x * (q.y / kBrickRows + bricks.y * (q.z / kBrickLayers));
            atomicOr(solidBricks[brick], 1u);
        }
        return;
    }
    // Cell q's byte (pass 1's) says whether faces q of the three components are solid: its own
    // bit or its -c neighbour's. Faces past the last cell along an axis look below them.
    bool inside = all(lessThan(q, n));
    uint byte = inside ? solidByte(q) : 0xffu;
    if ((byte & 0x2bu) == 0u) return; // bits 0, 1 (-x), 3 (-y), 5 (-z)
    for (int c = 0; c < 3; ++c)
        if (all(lessThan(q, faceCount(c)))) markFace(c, q);
    if (inside && (byte & 1u) != 0u) imageStore(pigment, q, vec4(0.0));
}
