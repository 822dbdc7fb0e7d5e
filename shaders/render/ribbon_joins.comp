// ribbonJoins: the direction of every sample of a speed-line queue's live segments along its line,
// shared by the pieces that meet there, so that the ribbon's edges are one continuous curve
// (effect_lines.geom offsets both ends of a piece across these directions instead of across the
// piece's own). The lines of consecutive segments weld bit for bit at their common pose
// (build_segment.comp), and the line is followed across that weld: a sample's neighbours are the
// samples before and after it along its source vertex's trail, in the newer or the older segment
// where it is a segment's end. The direction is the bisector of the two pieces that meet,
// t = normalize(d_in / |d_in| + d_out / |d_out|); at the ends of the trail, the one piece's
// direction. The ribbon keeps its width across the bisector (a bevelled corner, no mitre): ribbons
// are often wider than their pieces are long, and a mitre's inner point would then fold back over
// the pieces before it.
//
// One invocation per sample of every live segment. Chain entry i (newest first): x = the segment's
// first ring vertex, y = 1 where segment i + 1 is the frame just before (its newest samples are
// segment i's oldest), 0 where the trail starts afresh between them.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/effect_draw.h"
#include "shared/trajectory.h"

layout(local_size_x = MFX_RIBBON_JOINS_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Ring {
    TrajectoryVertex ring[];
};
layout(std430, binding = 1) readonly buffer Chain {
    uvec2 chain[];
};
layout(std430, binding = 2) writeonly buffer Joins {
    vec4 joins[]; // by ring vertex: xyz the unit direction (towards the older samples), w 0
};
layout(push_constant) uniform Constants {
    RibbonJoinConstants c;
};

vec3 at(uint segment, uint line, uint k) {
    return ring[chain[segment].x + line * c.perLine + k].position.xyz;
}

void main() {
    uint id = gl_GlobalInvocationID.x;
    uint perSegment = c.sourceVertices * c.perLine;
    if (id >= perSegment * c.segments) return;
    uint segment = id / perSegment;
    uint line = (id % perSegment) / c.perLine;
    uint k = id % c.perLine;
    uint last = c.perLine - 1u;

    vec3 p = at(segment, line, k);
    // The sample before (newer) and after (older) along the line, or p itself at the trail's ends.
    vec3 newer = p, older = p;
    if (k > 0u)
        newer = at(segment, line, k - 1u);
    else if (segment > 0u && chain[segment - 1u].y != 0u)
        newer = at(segment - 1u, line, last - 1u);
    if (k < last)
        older = at(segment, line, k + 1u);
    else if (segment + 1u < c.segments && chain[segment].y != 0u)
        older = at(segment + 1u, line, 1u);

    vec3 dIn = p - newer, dOut = older - p;
    float lIn = length(dIn), lOut = length(dOut);
    const float tiny = 1e-7;
    vec3 t = vec3(0.0);
    if (lIn > tiny && lOut > tiny) {
        vec3 sum = dIn / lIn + dOut / lOut;
        // Where the line turns back on itself there is no bisector: the way on.
        t = length(sum) > tiny ? normalize(sum) : dOut / lOut;
    } else if (lOut > tiny) {
        t = dOut / lOut;
    } else if (lIn > tiny) {
        t = dIn / lIn;
    }
    joins[chain[segment].x + line * c.perLine + k] = vec4(t, 0.0);
}
