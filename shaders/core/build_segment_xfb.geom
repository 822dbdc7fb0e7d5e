// buildSegmentXfb: the split trajectory method the way the source paper built it (Xu et al.,
// section 4.1): a geometry shader emits the segment of one source vertex and transform feedback
// (the paper's stream output) stores it into this frame's slot of the ring. Kept to measure
// against the compute pass (build_segment.comp), which the queue uses. A geometry invocation may
// emit at most maxGeometryOutputVertices vertices and maxGeometryTotalOutputComponents floats, so
// a segment is S + 1 <= 17 points of 16 floats here. Both frames' transforms are blended from
// their palettes (a geometry shader keeps nothing for the next frame without vertex-pipeline
// stores); the same code on the same palette gives the same bits, so the ends still weld.
// Twin: trajectory::buildSegment (core/trajectory/build_segment.cpp).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/skinning.h"
#include "shared/trajectory.h"

layout(points) in;
layout(points, max_vertices = 17) out; // MFX_TRAJECTORY_MAX_SUBSAMPLES + 1

layout(location = 0) flat in uint sourceIndex[];

layout(location = 0, xfb_buffer = 0, xfb_stride = 64, xfb_offset = 0) out vec4 outPosition;
layout(location = 1, xfb_buffer = 0, xfb_offset = 16) out vec4 outNormal;
layout(location = 2, xfb_buffer = 0, xfb_offset = 32) out vec4 outColour;
layout(location = 3, xfb_buffer = 0, xfb_offset = 48) out vec4 outVelocity;

layout(std430, binding = 0) readonly buffer Palettes {
    SkinJoint palettes[]; // two frames' palettes; push constants say which is which
};
layout(std430, binding = 1) readonly buffer Sources {
    SkinVertexIn sources[];
};
layout(std430, binding = 2) readonly buffer Colours {
    vec4 colours[];
};
layout(push_constant) uniform Constants {
    TrajectoryConstants c;
};

#define MFX_EMIT_POINT(index, p, n, col, vel)                                                    \
    {                                                                                             \
        outPosition = p;                                                                          \
        outNormal = n;                                                                            \
        outColour = col;                                                                          \
        outVelocity = vel;                                                                        \
        gl_Position = vec4(p.xyz, 1.0);                                                           \
        EmitVertex();                                                                             \
        EndPrimitive();                                                                           \
    }
#define MFX_TRAJECTORY_OUTPUT MFX_EMIT_POINT
#include "trajectory_segment.glsl"

#define NOW_AT(i) palettes[c.transformNow + (i)]
#define PREVIOUS_AT(i) palettes[c.transformPrevious + (i)]

void main() {
    uint v = sourceIndex[0];
    if (v >= c.vertexCount) return;
    SkinVertexIn source = sources[v];
    SkinJoint joints[4];
    vec4 weights = source.weights;
    MFX_LOAD_INFLUENCES(source, c.jointCount, NOW_AT, joints, weights)
    SkinJoint now = blendJoints(joints, weights);
    weights = source.weights;
    MFX_LOAD_INFLUENCES(source, c.jointCount, PREVIOUS_AT, joints, weights)
    SkinJoint previous = blendJoints(joints, weights);
    emitSegment(now, previous, source, colours[v], c.time, c.dt, 0u, c);
}
