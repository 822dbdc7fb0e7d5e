// Structures of the trajectory passes (core/trajectory/, shaders/core/build_segment.comp and
// shaders/core/build_trail.comp), shared by GLSL and C++.
#ifndef MFX_SHARED_TRAJECTORY_H
#define MFX_SHARED_TRAJECTORY_H

#include "common.h"

#define MFX_TRAJECTORY_GROUP_SIZE 64
// Sub-samples per segment: S pieces, S + 1 trajectory vertices per source vertex.
#define MFX_TRAJECTORY_MAX_SUBSAMPLES 16

MFX_SHARED_BEGIN

// One trajectory vertex: a source vertex at one sub-sample tau of one segment (tau = 0 at the
// segment's frame time, 1 at the previous frame's).
struct TrajectoryVertex {
    vec4 position; // xyz: world position; w: tau
    vec4 normal;   // xyz: unit normal; w: the sample's time, birth - tau * dt (seconds)
    vec4 color;    // rgb: the source's colour; a: its alpha times the attenuation at tau
    vec4 velocity; // xyz: impulse velocity (world units per second, times k); w: birth time
};

// Push constants of build_segment (one segment) and build_trail (the whole trail, unsplit).
struct TrajectoryConstants {
    uint vertexCount;       // source vertices
    uint jointCount;        // joints per palette
    uint subSamples;        // S, 1..MFX_TRAJECTORY_MAX_SUBSAMPLES
    uint outputBase;        // build_segment: first trajectory vertex of the slot written
    uint transformNow;      // build_segment: first per-vertex transform written this frame
    uint transformPrevious; // build_segment: first per-vertex transform of the previous frame
    uint segmentCount;      // build_trail: segments rebuilt (palettes hold segmentCount + 1)
    uint hasPrevious;       // build_segment: 0 on the first frame (the segment has no extent)
    float time;             // build_segment: the frame's time (birth time of the segment)
    float dt;               // build_segment: the frame's time step
    float impulseScale;     // k: loss coefficient of the impulse velocity
    float alphaStart;       // attenuation at tau = 0
    float alphaEnd;         // attenuation at tau = 1
    float alphaPower;       // attenuation(tau) = start + (end - start) * tau^power
    float pad0;
    float pad1;
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(TrajectoryVertex, 64);
MFX_CHECK_LAYOUT(TrajectoryVertex, normal, 16);
MFX_CHECK_LAYOUT(TrajectoryVertex, color, 32);
MFX_CHECK_LAYOUT(TrajectoryVertex, velocity, 48);
MFX_CHECK_SIZE(TrajectoryConstants, 64);
MFX_CHECK_LAYOUT(TrajectoryConstants, time, 32);
MFX_CHECK_LAYOUT(TrajectoryConstants, alphaPower, 52);
#endif

#endif
