// skinVertices: dual quaternion linear blending with scale, one vertex per invocation.
// Twin: anim::skinDualQuat (core/anim/skinning.cpp), same order of operations: align every
// influence with the first one of non-zero weight (the sign rule), blend the dual quaternions and
// the scales by weight, normalise, scale the vertex (the normal by 1/S), rotate and translate.
// docs/architecture.md "Formulas"; Kavan et al. 2008.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/skinning.h"
#include "dual_quat.glsl"

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

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= constants.vertexCount) return;
    SkinVertexIn v = vertices[i];
    // Influences naming a joint outside the palette are dropped (a GPU buffer is not checked).
    SkinJoint joints[4];
    vec4 weights = v.weights;
    for (int k = 0; k < 4; ++k) {
        if (v.joints[k] < constants.jointCount) {
            joints[k] = palette[v.joints[k]];
        } else {
            joints[k] = identityTransform();
            weights[k] = 0.0;
        }
    }
    SkinJoint t = blendJoints(joints, weights);
    skinned[i] = SkinVertexOut(vec4(transformPoint(t, v.position.xyz), 1.0),
                               vec4(transformNormal(t, v.normal.xyz), 0.0));
}
