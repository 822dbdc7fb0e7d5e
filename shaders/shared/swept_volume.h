// Structures of the swept-volume motion blur (render/kinds/swept_volume_pass.h;
// shaders/swept_volume_*.comp), shared by GLSL and C++. Wloka and Zeleznik 1996, "Interactive
// Real-Time Motion Blur": Sec. 3 (one segment), 3.4 (transparency), 4.2 (n segments), 4.3
// (rotation).
#ifndef MFX_SHARED_SWEPT_VOLUME_H
#define MFX_SHARED_SWEPT_VOLUME_H

#include "common.h"

#define MFX_SWEPT_GROUP_SIZE 64
// Segments of a piecewise linear sweep (Sec. 4.2); the ring holds one more position: now.
#define MFX_SWEPT_MAX_SEGMENTS 16

// The temporal filter whose weight over the exposure shapes the alpha (Sec. 3.4;
// scene::SweptFilter).
#define MFX_SWEPT_BOX 0u
#define MFX_SWEPT_RAMP 1u
#define MFX_SWEPT_TRIANGLE 2u
#define MFX_SWEPT_GAUSSIAN 3u

// Below this motion over the sweep (world units) the part counts as still: the same pose twice
// gives exactly zero, float noise in a re-skinned pose stays far below it.
#define MFX_SWEPT_STILL 1e-6

MFX_SHARED_BEGIN

// Push constants of swept_volume_record, swept_volume_motion and swept_volume_build.
struct SweptVolumeConstants {
    vec4 cameraPosition; // xyz: the camera, for the contour-line's visibility (Sec. 3.2)
    uint vertexCount;    // bound vertices
    uint triangleCount;  // bound triangles
    uint edgeCount;      // interior edges (two triangles each) of the bound part
    uint historySlots;   // positions per vertex in the ring: segments + 1
    uint newest;         // the slot holding this frame's position
    uint filled;         // slots holding a recorded position, 1..historySlots
    uint reset;          // 1: every slot takes this frame's position (no motion yet)
    uint segments;       // n of Sec. 4.2: recorded frames the sweep runs back through
    uint pieces;         // joining quads per segment, so the filter's shape shows
    uint temporalFilter; // MFX_SWEPT_*
    float alphaFloor;    // the least alpha anywhere (the paper's 0.1)
    uint pad0;
};

// Written by the passes each frame, read as indirect draw arguments and by the CPU.
struct SweptVolumeCounters {
    uint vertexCount; // VkDrawIndirectCommand of the translucent triangles
    uint instanceCount;
    uint firstVertex;
    uint firstInstance;
    vec4 motion;            // xyz: the part's motion over the sweep, now minus oldest (Sec. 4.2:
                            // the sum of the segments' motion vectors); w: its path length
    float extent;           // the part's extent along the motion (Sec. 3.4)
    float trailingAlpha;    // max(floor, 1 - length / extent) (Sec. 3.4)
    uint contourEdges;      // contour-line edges joined this frame
    uint trailingTriangles; // back triangles drawn at the oldest position
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(SweptVolumeConstants, 64);
MFX_CHECK_LAYOUT(SweptVolumeConstants, vertexCount, 16);
MFX_CHECK_LAYOUT(SweptVolumeConstants, alphaFloor, 56);
MFX_CHECK_SIZE(SweptVolumeCounters, 48);
MFX_CHECK_LAYOUT(SweptVolumeCounters, motion, 16);
MFX_CHECK_LAYOUT(SweptVolumeCounters, trailingAlpha, 36);
#endif

#endif
