// Structures of the coupling from trajectory segments to the smoke solver
// (fluid/segment_emitters.h, shaders/fluid/segment_emitters.comp), shared by GLSL and C++.
#ifndef MFX_SHARED_COUPLING_H
#define MFX_SHARED_COUPLING_H

#include "common.h"

#define MFX_COUPLING_GROUP_SIZE 64

MFX_SHARED_BEGIN

struct SegmentEmitterConstants {
    vec4 gridOrigin;       // xyz: world position of the grid's low corner; w: splat radius (world)
    uint firstVertex;      // first trajectory vertex of the segment in the ring
    uint vertexCount;      // the segment's vertices
    uint emitterCount;     // emitter records to write (<= vertexCount)
    uint firstEmitter;     // where in the emitter buffer they go
    float strength;        // emitter strength per second at full alpha
    uint samplesPerVertex; // S + 1: the segment is source-major, this many samples per source
    float pad1;
    float pad2;
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(SegmentEmitterConstants, 48);
MFX_CHECK_LAYOUT(SegmentEmitterConstants, firstVertex, 16);
MFX_CHECK_LAYOUT(SegmentEmitterConstants, strength, 32);
#endif

#endif
