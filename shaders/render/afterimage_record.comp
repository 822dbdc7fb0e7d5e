// afterimageRecord: writes this frame's skinned position of every bound vertex into the ring of
// recorded positions (Smith 2016, Sec. 4.1.1 "Recording Vertex Motion"; Sec. 5.1 step 1), and
// finds the fastest vertex's motion (for the relative speed threshold, Sec. 5.3 "Thresholding")
// and, for arcs, the longest recorded path Dmax (Sec. 5.3 "Influence").
#version 450
#extension GL_GOOGLE_include_directive : require
#include "afterimage_common.glsl"

layout(local_size_x = MFX_AFTERIMAGE_GROUP_SIZE) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= constants.vertexCount) return;
    vec4 p = vec4(skinned[i].position.xyz, 1.0);
    if (constants.reset != 0u) {
        // A new start (first frame, a jump, a new simulation): no motion recorded yet.
        for (uint s = 0; s < constants.historySlots; ++s)
            history[s * constants.vertexCount + i] = p;
    } else {
        history[constants.newest * constants.vertexCount + i] = p;
    }
    // Lengths are non-negative, so their float bits order like the floats.
    atomicMax(counters.fastestBits, floatBitsToUint(length(frameMotion(i))));
    if (constants.variant == MFX_AFTERIMAGE_MULTI)
        atomicMax(counters.longestBits, floatBitsToUint(pathLength(i)));
}
