// segmentEmitters: the coupling of motion to smoke (Xu et al., section 3.3: the segment's impulse
// velocity and colour go into the grid as impulses). Each emitter is one trajectory vertex of the
// newest segment. When the segment has more vertices than emitters, whole source vertices are
// picked evenly (every sample along the segment of each, so the swept path stays covered whatever
// the frame rate): emitter i is sample i % (S + 1) of source vertex
// floor((i / (S + 1)) * sources / picked). Each takes its position moved into the grid's
// frame (world units from the grid's low corner), its impulse velocity, its colour as pigment, and
// a strength scaled by its alpha (the attenuation along the segment). No readback: the emitter
// buffer feeds the solver's splat directly. Twin: fluid::segmentEmitters
// (fluid/segment_emitters.cpp).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/coupling.h"
#include "shared/fluid.h"
#include "shared/trajectory.h"

layout(local_size_x = MFX_COUPLING_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Ring {
    TrajectoryVertex trajectory[];
};
layout(std430, binding = 1) writeonly buffer Emitters {
    FluidEmitter emitters[];
};
layout(push_constant) uniform Constants {
    SegmentEmitterConstants c;
};

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= c.emitterCount || c.vertexCount == 0u) return;
    uint perVertex = max(c.samplesPerVertex, 1u);
    uint sources = c.vertexCount / perVertex;
    uint picked = max(c.emitterCount / perVertex, 1u);
    uint source = uint(float(i / perVertex) * (float(sources) / float(picked)));
    uint j = c.firstVertex + min(source * perVertex + i % perVertex, c.vertexCount - 1u);
    vec4 position = trajectory[j].position;
    vec4 colour = trajectory[j].color;
    vec4 velocity = trajectory[j].velocity;
    uint o = c.firstEmitter + i;
    emitters[o].positionRadius = vec4(position.xyz - c.gridOrigin.xyz, c.gridOrigin.w);
    emitters[o].velocityStrength = vec4(velocity.xyz, c.strength * colour.a);
    emitters[o].pigment = vec4(colour.rgb, 1.0);
}
