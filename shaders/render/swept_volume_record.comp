// sweptVolumeRecord: writes this frame's skinned position of every bound vertex into the ring of
// recorded positions, the n + 1 samples a piecewise linear sweep runs through (Wloka and Zeleznik
// 1996, Sec. 4.2: positions at t_0 ... t_n).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "swept_volume_common.glsl"

layout(local_size_x = MFX_SWEPT_GROUP_SIZE) in;

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
}
