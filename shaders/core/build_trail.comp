// buildTrail: the unsplit baseline the split method is measured against (Xu et al., section 5):
// every frame the whole trail is rebuilt from the palettes of the last L + 1 frames, skinning
// each source vertex at both ends of every segment. Invocation (v, j) writes segment j (0 = the
// newest) of source vertex v: S + 1 trajectory vertices, whatever the lifetime (the segments are
// spread over the dispatch's y dimension). For measurement only.
// Twin: trajectory::buildSegment (core/trajectory/build_segment.cpp), applied per segment.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/skinning.h"
#include "shared/trajectory.h"

layout(local_size_x = MFX_TRAJECTORY_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Palettes {
    SkinJoint palettes[]; // segmentCount + 1 palettes, the newest first
};
layout(std430, binding = 1) readonly buffer Sources {
    SkinVertexIn sources[];
};
layout(std430, binding = 2) readonly buffer Colours {
    vec4 colours[];
};
layout(std430, binding = 3) readonly buffer Times {
    float times[]; // segmentCount + 1 frame times, the newest first
};
layout(std430, binding = 4) writeonly buffer Ring {
    TrajectoryVertex trajectory[];
};
layout(push_constant) uniform Constants {
    TrajectoryConstants c;
};

#define MFX_TRAJECTORY_OUTPUT MFX_STORE_TRAJECTORY_VERTEX
#include "trajectory_segment.glsl"

#define NEWER_AT(i) palettes[newer + (i)]
#define OLDER_AT(i) palettes[older + (i)]

void main() {
    uint v = gl_GlobalInvocationID.x;
    uint j = gl_GlobalInvocationID.y;
    if (v >= c.vertexCount || j >= c.segmentCount) return;
    SkinVertexIn source = sources[v];
    uint newer = j * c.jointCount;
    uint older = (j + 1u) * c.jointCount;
    SkinJoint joints[4];
    vec4 weights = source.weights;
    MFX_LOAD_INFLUENCES(source, c.jointCount, NEWER_AT, joints, weights)
    SkinJoint now = blendJoints(joints, weights);
    weights = source.weights;
    MFX_LOAD_INFLUENCES(source, c.jointCount, OLDER_AT, joints, weights)
    SkinJoint previous = blendJoints(joints, weights);
    uint perVertex = clamp(c.subSamples, 1u, uint(MFX_TRAJECTORY_MAX_SUBSAMPLES)) + 1u;
    uint base = (j * c.vertexCount + v) * perVertex;
    emitSegment(now, previous, source, colours[v], times[j], times[j] - times[j + 1u], base, c);
}
