// One trajectory segment of one source vertex: S + 1 sub-samples between the vertex's transform
// at the frame's time (tau = 0) and at the previous frame's (tau = 1), each moved by the
// interpolated dual quaternion (Xu et al., eq. 3: (1 - tau) Q_t +- tau Q_{t-dt}, normalised), so
// arcs stay curved. The impulse velocity of each sample is the mean of the backward and forward
// differences along tau (one-sided at the ends) per second, times k; the alpha is the attenuation
// of tau (Xu et al., Algorithm 1). Included by build_segment.comp and build_trail.comp after they
// declare `TrajectoryVertex trajectory[]`. Twin: trajectory::buildSegment
// (core/trajectory/build_segment.cpp), same order of operations.
#ifndef MFX_TRAJECTORY_SEGMENT_GLSL
#define MFX_TRAJECTORY_SEGMENT_GLSL

#include "dual_quat.glsl"
#include "shared/trajectory.h"

// The compute passes' output: trajectory vertex `index` of the buffer `trajectory[]` the shader
// declares, member by member (a whole-struct store into a buffer trips a glslang code generation
// problem: mismatched struct types in OpStore).
#define MFX_STORE_TRAJECTORY_VERTEX(index, p, n, col, vel)                                       \
    {                                                                                             \
        trajectory[index].position = p;                                                           \
        trajectory[index].normal = n;                                                             \
        trajectory[index].color = col;                                                            \
        trajectory[index].velocity = vel;                                                         \
    }

float attenuation(float tau, TrajectoryConstants c) {
    float shaped = tau > 0.0 ? pow(tau, c.alphaPower) : 0.0;
    return c.alphaStart + (c.alphaEnd - c.alphaStart) * shaped;
}

void emitSegment(SkinJoint now, SkinJoint previous, SkinVertexIn v, vec4 colour, float birth,
                 float dt, uint base, TrajectoryConstants c) {
    uint s = clamp(c.subSamples, 1u, uint(MFX_TRAJECTORY_MAX_SUBSAMPLES));
    vec3 positions[MFX_TRAJECTORY_MAX_SUBSAMPLES + 1];
    vec3 normals[MFX_TRAJECTORY_MAX_SUBSAMPLES + 1];
    for (uint i = 0u; i <= s; ++i) {
        float tau = float(i) / float(s);
        SkinJoint t = interpolateTransform(now, previous, tau);
        positions[i] = transformPoint(t, v.position.xyz);
        normals[i] = transformNormal(t, v.normal.xyz);
    }
    // Sub-sample i lies dt / S after sub-sample i + 1.
    float perStep = dt > 0.0 ? float(s) / dt : 0.0;
    for (uint i = 0u; i <= s; ++i) {
        float tau = float(i) / float(s);
        vec3 velocity;
        if (i == 0u)
            velocity = (positions[0] - positions[1]) * perStep;
        else if (i == s)
            velocity = (positions[s - 1u] - positions[s]) * perStep;
        else
            velocity = 0.5 * ((positions[i - 1u] - positions[i]) * perStep +
                              (positions[i] - positions[i + 1u]) * perStep);
        MFX_TRAJECTORY_OUTPUT(base + i, vec4(positions[i], tau),
                              vec4(normals[i], birth - tau * dt),
                              vec4(colour.rgb, colour.a * attenuation(tau, c)),
                              vec4(velocity * c.impulseScale, birth));
    }
}

// The four palette entries and weights of a source vertex, influences outside the palette
// dropped (a GPU buffer is not checked). PALETTE_AT(i) reads entry i of the palette in use.
#define MFX_LOAD_INFLUENCES(v, jointCount, PALETTE_AT, joints, weights)                          \
    for (int k = 0; k < 4; ++k) {                                                                 \
        if (v.joints[k] < jointCount) {                                                           \
            joints[k] = PALETTE_AT(v.joints[k]);                                                  \
        } else {                                                                                  \
            joints[k] = identityTransform();                                                      \
            weights[k] = 0.0;                                                                     \
        }                                                                                         \
    }

#endif
