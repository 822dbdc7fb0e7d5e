// pigmentBounds: the box of cells whose pigment alpha exceeds a small threshold, so the smoke pass
// marches (and rasterises) only that box rather than the whole grid. It changes where the march
// runs, never what it computes beyond the threshold: the cells below it add about half an 8-bit
// level of opacity at most to a ray (render/smoke_pass.h, SmokeLook::pigmentThreshold). Follows
// shaders/fluid/emitter_bounds.comp, which bounds the splat the same way.
//
// One invocation per cell: each workgroup merges its cells' box in shared memory, then one
// invocation merges it into the global box with atomicMin/atomicMax on uints (the buffer is reset
// to an empty box before the dispatch). With MFX_SPARSE_PIGMENT, for a sparse grid: an indirect
// dispatch over its active list (two workgroups of 8x8x4 a brick, as the solver's stages), each
// invocation one cell of a stored brick, read from the pigment atlas.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "field_formats.glsl"
#include "shared/smoke_draw.h"

layout(local_size_x = MFX_PIGMENT_BOUNDS_GROUP_X, local_size_y = MFX_PIGMENT_BOUNDS_GROUP_Y,
       local_size_z = MFX_PIGMENT_BOUNDS_GROUP_Z) in;

layout(push_constant) uniform Dispatch {
    PigmentBoundsDispatch dispatch;
};
#ifdef MFX_SPARSE_PIGMENT
#include "shared/sparse_fluid.h"
layout(std430, binding = 0) readonly buffer PigmentAtlas {
    vec4 atlas[];
};
layout(std430, binding = 2) readonly buffer BrickTable {
    uint brickSlot[];
};
layout(std430, binding = 3) readonly buffer BrickList {
    BrickListHeader listHeader;
    uint listedBricks[];
};

// This invocation's cell and its pigment alpha.
float cellAlpha(out uvec3 cell) {
    uint index = listedBricks[gl_WorkGroupID.x >> 1];
    uvec3 n = dispatch.size.xyz / MFX_BRICK_SIZE;
    uvec3 brick = uvec3(index % n.x, (index / n.x) % n.y, index / (n.x * n.y));
    uvec3 l = gl_LocalInvocationID + uvec3(0u, 0u, 4u * (gl_WorkGroupID.x & 1u));
    cell = brick * MFX_BRICK_SIZE + l;
    return atlas[brickSlot[index] * MFX_BRICK_CELLS + l.x + 8u * (l.y + 8u * l.z)].a;
}
#else
layout(MFX_PIGMENT_FORMAT, binding = 0) uniform readonly image3D pigment;

float cellAlpha(out uvec3 cell) {
    cell = gl_GlobalInvocationID;
    return all(lessThan(cell, dispatch.size.xyz)) ? imageLoad(pigment, ivec3(cell)).a : 0.0;
}
#endif
layout(std430, binding = 1) buffer Bounds {
    PigmentBounds bounds;
};

shared uint groupLow[3];
shared uint groupHigh[3];

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        groupLow[0] = groupLow[1] = groupLow[2] = 0xffffffffu;
        groupHigh[0] = groupHigh[1] = groupHigh[2] = 0u;
    }
    barrier();
    uvec3 cell;
    float alpha = cellAlpha(cell);
    if (all(lessThan(cell, dispatch.size.xyz)) && alpha > dispatch.threshold) {
        for (int axis = 0; axis < 3; ++axis) {
            atomicMin(groupLow[axis], cell[axis]);
            atomicMax(groupHigh[axis], cell[axis]);
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && groupLow[0] <= groupHigh[0]) {
        for (int axis = 0; axis < 3; ++axis) {
            atomicMin(bounds.low[axis], groupLow[axis]);
            atomicMax(bounds.high[axis], groupHigh[axis]);
        }
    }
}
