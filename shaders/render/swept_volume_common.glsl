// What the swept-volume passes share (render/kinds/swept_volume_pass.h): one descriptor layout for the
// three stages, the ring of recorded positions and the alpha along the sweep.
// Wloka and Zeleznik 1996, "Interactive Real-Time Motion Blur", Sec. 3-4.
#ifndef MFX_SWEPT_VOLUME_COMMON_GLSL
#define MFX_SWEPT_VOLUME_COMMON_GLSL

#include "shared/skinning.h"
#include "shared/swept_volume.h"
#include "shared/trajectory.h"

layout(push_constant) uniform Constants {
    SweptVolumeConstants constants;
};
// The bound vertices skinned for this frame.
layout(std430, binding = 0) readonly buffer Skinned {
    SkinVertexOut skinned[];
};
// The ring of recorded positions, slot-major: history[slot * vertexCount + vertex].
layout(std430, binding = 1) buffer History {
    vec4 history[];
};
layout(std430, binding = 2) readonly buffer Colours {
    vec4 colours[];
};
// Bound triangles, 3 vertex indices each.
layout(std430, binding = 3) readonly buffer Triangles {
    uint triangles[];
};
// Interior edges, 6 words each: the two triangles beside it, then the edge's two vertices as the
// first triangle indexes them, then as the second does (a vertex split at a seam has two indices).
layout(std430, binding = 4) readonly buffer Edges {
    uint edges[];
};
// Translucent triangles: joining quads (2 triangles each) and the trailing side.
layout(std430, binding = 5) writeonly buffer Output {
    TrajectoryVertex outputVertices[];
};
layout(std430, binding = 6) buffer Counters {
    SweptVolumeCounters counters;
};

// The slot `back` frames before this one (0: this frame), back < constants.filled.
uint slotBack(uint back) {
    return (constants.newest + constants.historySlots - back) % constants.historySlots;
}

vec3 recorded(uint vertex, uint back) {
    return history[slotBack(back) * constants.vertexCount + vertex].xyz;
}

// Segments the sweep has this frame: n, or fewer while the ring fills.
uint sweptSegments() {
    return min(constants.segments, constants.filled - 1u);
}

// Where a vertex was `back` frames ago, between ring slots: its own recorded path, so the
// trailing side and each contour-line keep the orientation they had then (Sec. 4.3).
vec3 pathAt(uint vertex, float back) {
    back = clamp(back, 0.0, float(constants.filled - 1u));
    uint b0 = uint(floor(back));
    uint b1 = min(b0 + 1u, constants.filled - 1u);
    return mix(recorded(vertex, b0), recorded(vertex, b1), back - float(b0));
}

// erf, Abramowitz and Stegun 7.1.26 (absolute error below 1.5e-7).
float erfApprox(float x) {
    float t = 1.0 / (1.0 + 0.3275911 * abs(x));
    float y = 1.0 - ((((1.061405429 * t - 1.453152027) * t + 1.421413741) * t - 0.284496736) * t +
                     0.254829592) * t * exp(-x * x);
    return sign(x) * y;
}

// The share of the temporal filter's weight over the exposure that lies at ages 0..s (s = 0 now,
// 1 at the oldest sample). Sec. 3.4 lets the transparency model the filter (box, ramp, triangle,
// Gaussian); the filter here is a weight over the exposure: box uniform, ramp falling linearly
// with age (the latest instant counts most), triangle and Gaussian (sigma = 1/6) peaked at its
// middle.
float filterShare(float s) {
    s = clamp(s, 0.0, 1.0);
    if (constants.temporalFilter == MFX_SWEPT_BOX) return s;
    if (constants.temporalFilter == MFX_SWEPT_RAMP) return 1.0 - (1.0 - s) * (1.0 - s);
    if (constants.temporalFilter == MFX_SWEPT_TRIANGLE)
        return s < 0.5 ? 2.0 * s * s : 1.0 - 2.0 * (1.0 - s) * (1.0 - s);
    const float k = 0.5 / (sqrt(2.0) / 6.0); // half the exposure in units of sigma * sqrt(2)
    return 0.5 * (erfApprox((s - 0.5) * 2.0 * k) / erfApprox(k) + 1.0);
}

// Alpha at place s along the sweep: opaque at the leading side (s = 0), the trailing value at
// s = 1 (Sec. 3.4), in between falling with the filter's weight still to come, never below the
// floor. A cumulative share only grows, so alpha never rises along a joining strip.
float sweptAlpha(float s) {
    float trailing = counters.trailingAlpha;
    return max(constants.alphaFloor, trailing + (1.0 - trailing) * (1.0 - filterShare(s)));
}

#endif
