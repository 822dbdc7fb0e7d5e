// project: u -= (p_high - p_low) / h on every face not on a wall; p = 0 across open faces, wrapped
// across periodic ones (docs/fluid.md). Twin: fluid/reference/project.cpp. One dispatch per
// component.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, r32f) uniform image3D velocityX;
layout(binding = 2, r32f) uniform image3D velocityY;
layout(binding = 3, r32f) uniform image3D velocityZ;
layout(binding = 4, r32f) uniform readonly image3D pressure;

float pressureAt(ivec3 q, int axis) {
    int n = cellCount()[axis];
    if (q[axis] >= 0 && q[axis] < n) return imageLoad(pressure, q).r;
    if (periodicAxis(axis)) {
        q[axis] = wrapIndex(q[axis], n);
        return imageLoad(pressure, q).r;
    }
    return 0.0;
}

void main() {
    int c = int(kTarget);
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(q, faceCount(c))) || wallNormalFace(c, q)) return;
    ivec3 below = q;
    below[c] -= 1;
    float gradient = (pressureAt(q, c) - pressureAt(below, c)) * inverseCellSize();
    if (c == 0)
        imageStore(velocityX, q, vec4(imageLoad(velocityX, q).r - gradient));
    else if (c == 1)
        imageStore(velocityY, q, vec4(imageLoad(velocityY, q).r - gradient));
    else
        imageStore(velocityZ, q, vec4(imageLoad(velocityZ, q).r - gradient));
}
