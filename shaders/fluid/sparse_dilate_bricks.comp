// The active set's rebuild, 3: the wanted set grown by the advection's reach (in bricks) along one
// axis (kTarget); three passes make the box around every wanted brick. One invocation a virtual
// brick. Twin: SparseBricks::dilate.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_rebuild_common.glsl"

layout(std430, binding = 2) readonly buffer WantedIn {
    uint wantedIn[];
};
layout(std430, binding = 3) writeonly buffer WantedOut {
    uint wantedOut[];
};

void main() {
    int index = flatInvocation();
    if (index >= int(rebuild.counts.y)) return;
    int axis = int(kTarget);
    ivec3 b = brickAt(index);
    int reach = int(rebuild.counts.x);
    int n = brickCount()[axis];
    uint any = 0u;
    for (int d = max(b[axis] - reach, 0); d <= min(b[axis] + reach, n - 1); ++d) {
        ivec3 other = b;
        other[axis] = d;
        any |= wantedIn[brickIndex(other)] & MFX_BRICK_WANTED;
    }
    wantedOut[index] = any;
}
