// markSolids: the sub-step's moving solids put into the grid (docs/fluid.md, "Solids"; Bridson,
// "Fluid Simulation for Computer Graphics", 2nd ed., ch. 5: u·n = u_solid·n on the faces between
// fluid and solid; Crane, Llamas, Tariq, GPU Gems 3 ch. 30: the obstacle voxelised into the grid
// every step with its surface's velocity). Twin: fluid/reference/mark_solids.cpp. Each solid is a
// capsule (shared::FluidSolid) where the step ends, with its two ends' velocities.
//
// Two dispatches (kPass, constant id 11):
//   0  over the cells: the first capsule holding the cell's centre into solidCells[].x
//      (shaders/fluid/fluid_solids.glsl), and a solid cell's pigment set to 0;
//   1  over cells + 1 along each axis: every solid face of each component takes the solid's
//      velocity at the face (the capsule holding the cell below it, else the one above), and each
//      cell's solid-neighbour bits go into solidCells[].y.
// Both write in place: pass 0 only cells it alone owns, pass 1 only faces and words pass 0 did not.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#define MFX_MARKS_SOLIDS
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

layout(constant_id = 11) const uint kPass = 0u;

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

// 1-based index of the first solid holding x; 0 for none.
uint holderOf(vec3 x) {
    uint count = uint(solids.length());
    for (uint i = 0u; i < count; ++i)
        if (insideSolid(solids[i], x)) return i + 1u;
    return 0u;
}

void markCell(ivec3 q) {
    uint holder = holderOf(cellCentre(q));
    solidCells[cellElement(q)].x = holder;
    if (holder != 0u) imageStore(pigment, q, vec4(0.0));
}

// The 1-based holder of the solid cell beside face q of component c: below first, then above.
uint faceHolder(int c, ivec3 q) {
    ivec3 below = q;
    below[c] -= 1;
    if (below[c] < 0 && periodicAxis(c)) below[c] = cellCount()[c] - 1;
    if (below[c] >= 0) {
        uint holder = solidCells[cellElement(below)].x;
        if (holder != 0u) return holder;
    }
    ivec3 above = q;
    if (above[c] >= cellCount()[c] && periodicAxis(c)) above[c] = 0;
    return above[c] < cellCount()[c] ? solidCells[cellElement(above)].x : 0u;
}

void markFace(int c, ivec3 q) {
    if (!solidFace(c, q)) return;
    FluidSolid s = solids[faceHolder(c, q) - 1u];
    vec3 x = facePosition(c, q);
    float v = mix(s.velocityA.xyz, s.velocityB.xyz, axisParameter(s, x))[c];
    if (c == 0)
        imageStore(velocityX, q, vec4(MFX_STORED(v)));
    else if (c == 1)
        imageStore(velocityY, q, vec4(MFX_STORED(v)));
    else
        imageStore(velocityZ, q, vec4(MFX_STORED(v)));
}

// Bit s: the neighbour on side s is a solid cell (one inside the grid, or wrapped).
uint neighbourBits(ivec3 q) {
    uint bits = 0u;
    for (int side = 0; side < 6; ++side) {
        int axis = side / 2;
        NeighbourRef ref = neighbourRef(axis, q[axis] + ((side & 1) == 0 ? -1 : 1));
        ivec3 neighbour = q;
        neighbour[axis] = ref.index;
        if (ref.value && solidCells[cellElement(neighbour)].x != 0u) bits |= 1u << uint(side);
    }
    return bits;
}

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (kPass == 0u) {
        if (all(lessThan(q, cellCount()))) markCell(q);
        return;
    }
    for (int c = 0; c < 3; ++c)
        if (all(lessThan(q, faceCount(c)))) markFace(c, q);
    if (all(lessThan(q, cellCount()))) solidCells[cellElement(q)].y = neighbourBits(q);
}
