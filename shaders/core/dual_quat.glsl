// Dual quaternion helpers shared by the skinning and trajectory shaders. Quaternions are vec4
// (x, y, z, w); a rigid transform with scale is a SkinJoint (real, dual, scale: M = T * R * S).
// Twins: math::DualQuat (core/math/dual_quat.cpp) and anim::blendJoints / anim::applyTransform
// (core/anim/skinning.cpp) and trajectory::interpolateTransform (core/trajectory/build_segment.cpp),
// in the same order of operations. docs/architecture.md "Formulas"; Kavan et al.
// 2008.
#ifndef MFX_DUAL_QUAT_GLSL
#define MFX_DUAL_QUAT_GLSL

#include "shared/skinning.h"

vec4 quatMul(vec4 a, vec4 b) {
    return vec4(a.w * b.xyz + b.w * a.xyz + cross(a.xyz, b.xyz), a.w * b.w - dot(a.xyz, b.xyz));
}

vec3 quatRotate(vec4 q, vec3 v) {
    vec3 uv = cross(q.xyz, v);
    vec3 uuv = cross(q.xyz, uv);
    return v + ((uv * q.w) + uuv) * 2.0;
}

// The identity: what a vertex without any influence is moved by.
SkinJoint identityTransform() {
    return SkinJoint(vec4(0.0, 0.0, 0.0, 1.0), vec4(0.0), vec4(1.0, 1.0, 1.0, 0.0));
}

// Blends four joints by weight: every influence aligned with the first one of positive weight
// (the sign rule), dual quaternions and scales blended by weight, the dual quaternion normalised.
// An influence whose weight is not positive is skipped; no positive weight gives the identity.
SkinJoint blendJoints(SkinJoint joints[4], vec4 weights) {
    int first = 0;
    while (first < 3 && !(weights[first] > 0.0))
        ++first;
    if (!(weights[first] > 0.0)) return identityTransform();
    vec4 reference = joints[first].real;
    vec4 real = vec4(0.0);
    vec4 dual = vec4(0.0);
    vec3 scale = vec3(0.0);
    float total = 0.0;
    for (int k = 0; k < 4; ++k) {
        if (!(weights[k] > 0.0)) continue;
        float w = dot(joints[k].real, reference) < 0.0 ? -weights[k] : weights[k];
        real += w * joints[k].real;
        dual += w * joints[k].dual;
        scale += weights[k] * joints[k].scale.xyz;
        total += weights[k];
    }
    scale /= total; // weights that do not sum to 1 still blend the scale as an average
    float len = length(real);
    return SkinJoint(real / len, dual / len, vec4(scale, 0.0));
}

// Moves a bind-pose point: scaled, rotated, translated.
vec3 transformPoint(SkinJoint t, vec3 p) {
    vec4 conjugate = vec4(-t.real.xyz, t.real.w);
    vec3 translation = 2.0 * quatMul(t.dual, conjugate).xyz;
    return quatRotate(t.real, t.scale.xyz * p) + translation;
}

// Moves a bind-pose normal: divided by the scale, rotated, normalised.
vec3 transformNormal(SkinJoint t, vec3 n) {
    return normalize(quatRotate(t.real, n / t.scale.xyz));
}

// (1 - tau) a + tau b with the sign rule (b negated when the rotation parts point apart),
// normalised; the scale blended linearly. a at tau = 0, b at tau = 1, bit for bit (0 * x + y = y
// and -b moves points exactly as b does).
SkinJoint interpolateTransform(SkinJoint a, SkinJoint b, float tau) {
    float s = dot(a.real, b.real) < 0.0 ? -tau : tau;
    vec4 real = (1.0 - tau) * a.real + s * b.real;
    vec4 dual = (1.0 - tau) * a.dual + s * b.dual;
    vec3 scale = (1.0 - tau) * a.scale.xyz + tau * b.scale.xyz;
    float len = length(real);
    return SkinJoint(real / len, dual / len, vec4(scale, 0.0));
}

#endif
