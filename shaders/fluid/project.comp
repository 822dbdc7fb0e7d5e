// project: u -= (p_high - p_low) / h on every face not on a wall; p = 0 across open faces, wrapped
// across periodic ones (docs/fluid.md). Twin: fluid/reference/project.cpp. One dispatch per
// component, writing every face of it (unchanged on walls) to a buffer that the solver copies
// into the component's image.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityX;
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityY;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityZ;
layout(binding = 4, MFX_PRESSURE_FORMAT) uniform readonly image3D pressure;
layout(std430, binding = 5) writeonly buffer Out {
    float outValues[];
};

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
    if (any(greaterThanEqual(q, faceCount(c)))) return;
    float value = c == 0 ? imageLoad(velocityX, q).r
                         : (c == 1 ? imageLoad(velocityY, q).r : imageLoad(velocityZ, q).r);
    if (!wallNormalFace(c, q)) {
        ivec3 below = q;
        below[c] -= 1;
        float gradient = (pressureAt(q, c) - pressureAt(below, c)) * inverseCellSize();
        value -= gradient;
    }
    outValues[faceElement(c, q)] = value;
}
