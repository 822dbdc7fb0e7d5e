// ribbonDistance: each sample's distance along its speed-line from where the line began, for a
// texture tiled by distance (ribbon_texture.glsl): the pattern is fixed on the path as it is drawn,
// the same number of repeats per metre however fast the line was drawn. A segment's distances are
// found once, the frame it is written, and kept with the ring (render/kinds/speed_lines_pass.cpp):
// its oldest sample is the previous segment's newest, bit for bit (build_segment.comp), so it
// starts from that sample's distance, and each sample towards the head adds the piece's length,
// D(k) = D(k + 1) + |p(k) - p(k + 1)| (k = 0 the newest). A line that starts afresh (no previous
// segment, or a gap) starts from 0.
//
// One invocation per line; each walks the listed segments oldest first, so that a segment listed
// after its predecessor reads the distance this invocation has just written. Entry i: x = the
// segment's first ring vertex, y = the previous segment's first ring vertex, or
// MFX_RIBBON_NO_SEGMENT.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/effect_draw.h"
#include "shared/trajectory.h"

layout(local_size_x = MFX_RIBBON_DISTANCE_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Ring {
    TrajectoryVertex ring[];
};
layout(std430, binding = 1) readonly buffer Segments {
    uvec2 segments[];
};
layout(std430, binding = 2) buffer Distances {
    float distances[]; // by ring vertex
};
layout(push_constant) uniform Constants {
    RibbonDistanceConstants c;
};

void main() {
    uint line = gl_GlobalInvocationID.x;
    if (line >= c.sourceVertices) return;
    uint last = c.perLine - 1u;
    for (uint s = 0u; s < c.segments; ++s) {
        uint first = segments[s].x + line * c.perLine;
        uint previous = segments[s].y;
        float d = previous == MFX_RIBBON_NO_SEGMENT ? 0.0 : distances[previous + line * c.perLine];
        distances[first + last] = d;
        for (uint k = last; k > 0u; --k) {
            d += distance(ring[first + k].position.xyz, ring[first + k - 1u].position.xyz);
            distances[first + k - 1u] = d;
        }
    }
}
