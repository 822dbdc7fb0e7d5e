// What the afterimage passes share (render/kinds/afterimage_pass.h): one descriptor layout for the
// four stages, the ring of recorded positions, and the per-vertex random value.
// Smith 2016, "Afterimage Toon Blur": chapter 4 (single afterimage), chapter 5 (multi-afterimage).
#ifndef MFX_AFTERIMAGE_COMMON_GLSL
#define MFX_AFTERIMAGE_COMMON_GLSL

#include "shared/afterimage.h"
#include "shared/skinning.h"
#include "shared/trajectory.h"

layout(push_constant) uniform Constants {
    AfterimageConstants constants;
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
// Per vertex: where it is drawn (smear), xyz + w 1 when pushed back; velocity.xyz its push,
// velocity.w how far back along its recorded path it reaches (multi).
layout(std430, binding = 3) buffer Pushed {
    TrajectoryVertex pushed[];
};
// Triangles (smear: 3 indices each) or edges (multi: 2 indices each) of the bound mesh part.
layout(std430, binding = 4) readonly buffer Primitives {
    uint primitives[];
};
// Speed-line pieces (2 vertices each) or arc triangles (multi).
layout(std430, binding = 5) writeonly buffer Output {
    TrajectoryVertex outputVertices[];
};
// The triangles of the smear that have a pushed vertex (indices into Pushed).
layout(std430, binding = 6) writeonly buffer Indices {
    uint drawnIndices[];
};
layout(std430, binding = 7) buffer Counters {
    AfterimageCounters counters;
};
// What afterimage_smear.comp decides per vertex, before afterimage_weld.comp makes the copies of a
// seam vertex agree (then Pushed).
layout(std430, binding = 8) buffer Decided {
    TrajectoryVertex decided[];
};
// The copies of each vertex at one bind-pose position: vertexCount + 1 offsets into this buffer,
// then each vertex's group of copies in index order (render/effect_geometry.h, weldByPosition).
layout(std430, binding = 9) readonly buffer Copies {
    uint copies[];
};

// The first copy of a vertex (the lowest index at its bind-pose position).
uint firstCopy(uint vertex) {
    return copies[copies[vertex]];
}

// The slot `back` frames before this one (0: this frame), back < constants.filled.
uint slotBack(uint back) {
    return (constants.newest + constants.historySlots - back) % constants.historySlots;
}

vec3 recorded(uint vertex, uint back) {
    return history[slotBack(back) * constants.vertexCount + vertex].xyz;
}

// This frame's motion of a vertex, m_i^t = p_i^t - p_i^(t-1) (Smith 2016, Sec. 4.1.1); zero on the
// first recorded frame.
vec3 frameMotion(uint vertex) {
    if (constants.filled < 2) return vec3(0.0);
    return recorded(vertex, 0) - recorded(vertex, 1);
}

// Recorded positions an arc runs through this frame (no more than the ring holds yet).
uint arcImages() {
    return min(constants.afterimages, constants.filled - 1);
}

// D_i of Smith 2016, Sec. 5.3: the length of the vertex's recorded path over the arc.
float pathLength(uint vertex) {
    float length_ = 0.0;
    for (uint b = 0; b < arcImages(); ++b)
        length_ += length(recorded(vertex, b) - recorded(vertex, b + 1));
    return length_;
}

// A 32-bit integer hash (lowbias32): the random factor R_i is a function of the vertex index
// alone, so it is the same every frame, every run and while paused (Smith 2016, Sec. 5.3
// "Randomization": time invariant, or the smear flickers at a standstill).
uint hashVertex(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
float vertexRandom(uint vertex) {
    return float(hashVertex(vertex) >> 8) * (1.0 / 16777216.0);
}

// Alpha along a push or an arc, s = 0 at the live mesh, 1 at the far end: monotone in s.
float alphaAt(float s) {
    return constants.alphaStart +
           (constants.alphaEnd - constants.alphaStart) * pow(s, constants.alphaPower);
}

#endif
