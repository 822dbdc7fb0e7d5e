// Structures of the skinning pass (core/anim/skin_vertices.h, shaders/core/skin_vertices.comp),
// shared by GLSL and C++.
#ifndef MFX_SHARED_SKINNING_H
#define MFX_SHARED_SKINNING_H

#include "common.h"

#define MFX_SKIN_GROUP_SIZE 64

MFX_SHARED_BEGIN

// One joint of the palette: its matrix split as T * R * S, R and T as a unit dual quaternion.
struct SkinJoint {
    vec4 real;  // rotation quaternion (x, y, z, w)
    vec4 dual;  // 0.5 * translation * rotation (x, y, z, w)
    vec4 scale; // xyz: per-axis scale; w unused
};

// A bind-pose vertex with its influences.
struct SkinVertexIn {
    vec4 position; // xyz; w unused
    vec4 normal;   // xyz; w unused
    uvec4 joints;  // indices into the palette
    vec4 weights;  // summing to 1
};

// A skinned vertex.
struct SkinVertexOut {
    vec4 position; // xyz; w = 1
    vec4 normal;   // xyz unit; w = 0
};

struct SkinConstants {
    uint vertexCount;
    uint jointCount;
    uint pad0;
    uint pad1;
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(SkinJoint, 48);
MFX_CHECK_LAYOUT(SkinJoint, dual, 16);
MFX_CHECK_LAYOUT(SkinJoint, scale, 32);
MFX_CHECK_SIZE(SkinVertexIn, 64);
MFX_CHECK_LAYOUT(SkinVertexIn, normal, 16);
MFX_CHECK_LAYOUT(SkinVertexIn, joints, 32);
MFX_CHECK_LAYOUT(SkinVertexIn, weights, 48);
MFX_CHECK_SIZE(SkinVertexOut, 32);
MFX_CHECK_SIZE(SkinConstants, 16);
#endif

#endif
