// skinVertices: dual quaternion linear blending with scale, one vertex per invocation.
// Twin: anim::skinDualQuat (core/anim/skinning.cpp), same order of operations: align every
// influence with the first one of non-zero weight (the sign rule), blend the dual quaternions and
// the scales by weight, normalise, scale the vertex (the normal by 1/S), rotate and translate.
// DESIGN.md "Formulas"; Kavan et al. 2008.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/skinning.h"

layout(local_size_x = MFX_SKIN_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Palette {
    SkinJoint palette[];
};
layout(std430, binding = 1) readonly buffer Input {
    SkinVertexIn vertices[];
};
layout(std430, binding = 2) writeonly buffer Output {
    SkinVertexOut skinned[];
};
layout(push_constant) uniform Constants {
    SkinConstants constants;
};

// Quaternions as (x, y, z, w).
vec4 quatMul(vec4 a, vec4 b) {
    return vec4(a.w * b.xyz + b.w * a.xyz + cross(a.xyz, b.xyz), a.w * b.w - dot(a.xyz, b.xyz));
}
vec3 rotate(vec4 q, vec3 v) {
    vec3 uv = cross(q.xyz, v);
    vec3 uuv = cross(q.xyz, uv);
    return v + ((uv * q.w) + uuv) * 2.0;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= constants.vertexCount) return;
    SkinVertexIn v = vertices[i];
    // Influences naming a joint outside the palette are dropped (a GPU buffer is not checked).
    vec4 weights = v.weights;
    for (int k = 0; k < 4; ++k)
        if (v.joints[k] >= constants.jointCount) weights[k] = 0.0;
    int first = 0;
    while (first < 3 && !(weights[first] > 0.0))
        ++first;
    if (!(weights[first] > 0.0)) { // no influence: the vertex stays where it is
        skinned[i] = SkinVertexOut(vec4(v.position.xyz, 1.0), vec4(normalize(v.normal.xyz), 0.0));
        return;
    }
    vec4 reference = palette[v.joints[first]].real;
    vec4 real = vec4(0.0);
    vec4 dual = vec4(0.0);
    vec3 scale = vec3(0.0);
    float total = 0.0;
    for (int k = 0; k < 4; ++k) {
        if (!(weights[k] > 0.0)) continue;
        SkinJoint joint = palette[v.joints[k]];
        float w = dot(joint.real, reference) < 0.0 ? -weights[k] : weights[k];
        real += w * joint.real;
        dual += w * joint.dual;
        scale += weights[k] * joint.scale.xyz;
        total += weights[k];
    }
    scale /= total; // weights that do not sum to 1 still blend the scale as an average
    float len = length(real);
    real /= len;
    dual /= len;
    vec4 conjugate = vec4(-real.xyz, real.w);
    vec3 translation = 2.0 * quatMul(dual, conjugate).xyz;
    vec3 position = rotate(real, scale * v.position.xyz) + translation;
    vec3 normal = normalize(rotate(real, v.normal.xyz / scale));
    skinned[i] = SkinVertexOut(vec4(position, 1.0), vec4(normal, 0.0));
}
