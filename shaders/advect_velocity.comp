// advectVelocity: semi-Lagrangian advection of each MAC face component (docs/fluid.md; Stam 1999,
// eq. 7), then the per-second drag, u *= exp(-drag * dt). Twin: fluid/reference/advect_velocity.cpp.
// One dispatch per component, writing a buffer that the solver copies into the component's image.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, r32f) uniform readonly image3D velocityX;
layout(binding = 2, r32f) uniform readonly image3D velocityY;
layout(binding = 3, r32f) uniform readonly image3D velocityZ;
layout(std430, binding = 4) writeonly buffer Out {
    float outValues[];
};

float loadVelocity(int c, ivec3 index) {
    return c == 0 ? imageLoad(velocityX, index).r
                  : (c == 1 ? imageLoad(velocityY, index).r : imageLoad(velocityZ, index).r);
}

#include "fluid_sampling.glsl"

void main() {
    int c = int(kTarget);
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(q, faceCount(c)))) return;
    float value = 0.0;
    if (!wallNormalFace(c, q))
        value = sampleVelocity(c, backTrace(facePosition(c, q))) * exp(-params.cell.w * timeStep());
    outValues[faceElement(c, q)] = flushTiny(value);
}
