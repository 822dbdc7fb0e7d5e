// buildSegment: the split trajectory method (Xu et al., section 3.2): one segment per frame,
// between the previous frame and this one, written into this frame's slot of the ring. One source
// vertex per invocation: its skinning transform at t is blended once from this frame's palette
// and kept for the next frame, whose segment starts where this one ends (the previous transform
// is read back, not recomputed, so the ends weld bit for bit). Writes S + 1 <= 17 trajectory
// vertices, whatever the lifetime. Twin: trajectory::buildSegment (core/trajectory/build_segment.cpp).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/skinning.h"
#include "shared/trajectory.h"

layout(local_size_x = MFX_TRAJECTORY_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Palette {
    SkinJoint palette[];
};
layout(std430, binding = 1) readonly buffer Sources {
    SkinVertexIn sources[];
};
layout(std430, binding = 2) readonly buffer Colours {
    vec4 colours[];
};
layout(std430, binding = 3) buffer Transforms {
    SkinJoint transforms[]; // two frames' per-vertex transforms, ping-ponged
};
layout(std430, binding = 4) writeonly buffer Ring {
    TrajectoryVertex trajectory[];
};
layout(push_constant) uniform Constants {
    TrajectoryConstants c;
};

#define MFX_TRAJECTORY_OUTPUT MFX_STORE_TRAJECTORY_VERTEX
#include "trajectory_segment.glsl"

#define PALETTE_AT(i) palette[i]

void main() {
    uint v = gl_GlobalInvocationID.x;
    if (v >= c.vertexCount) return;
    SkinVertexIn source = sources[v];
    SkinJoint joints[4];
    vec4 weights = source.weights;
    MFX_LOAD_INFLUENCES(source, c.jointCount, PALETTE_AT, joints, weights)
    SkinJoint now = blendJoints(joints, weights);
    SkinJoint previous = now;
    if (c.hasPrevious != 0u) previous = transforms[c.transformPrevious + v];
    transforms[c.transformNow + v].real = now.real;
    transforms[c.transformNow + v].dual = now.dual;
    transforms[c.transformNow + v].scale = now.scale;
    uint perVertex = clamp(c.subSamples, 1u, uint(MFX_TRAJECTORY_MAX_SUBSAMPLES)) + 1u;
    emitSegment(now, previous, source, colours[v], c.time, c.dt, c.outputBase + v * perVertex, c);
}
