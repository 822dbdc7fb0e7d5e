// advectPigment: semi-Lagrangian advection of the RGBA pigment, then the per-second fade
// (docs/fluid.md). Twin: fluid/reference/advect_pigment.cpp. Writes a buffer that the solver copies
// into the pigment image.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, r32f) uniform readonly image3D velocityX;
layout(binding = 2, r32f) uniform readonly image3D velocityY;
layout(binding = 3, r32f) uniform readonly image3D velocityZ;
layout(binding = 4, rgba32f) uniform readonly image3D pigmentIn;
layout(std430, binding = 5) writeonly buffer PigmentOut {
    vec4 pigmentOut[];
};

float loadVelocity(int c, ivec3 index) {
    return c == 0 ? imageLoad(velocityX, index).r
                  : (c == 1 ? imageLoad(velocityY, index).r : imageLoad(velocityZ, index).r);
}

#include "fluid_sampling.glsl"

vec4 fetchPigment(ivec3 index) {
    return imageLoad(pigmentIn, resolveCell(index));
}

vec4 samplePigment(vec3 x) {
    vec3 g = gridCoordinate(x, vec3(0.5));
    vec3 base = floor(g);
    vec3 f = g - base;
    ivec3 i0 = ivec3(base);
    vec4 c00 = lerpValue(fetchPigment(i0 + ivec3(0, 0, 0)), fetchPigment(i0 + ivec3(1, 0, 0)), f.x);
    vec4 c10 = lerpValue(fetchPigment(i0 + ivec3(0, 1, 0)), fetchPigment(i0 + ivec3(1, 1, 0)), f.x);
    vec4 c01 = lerpValue(fetchPigment(i0 + ivec3(0, 0, 1)), fetchPigment(i0 + ivec3(1, 0, 1)), f.x);
    vec4 c11 = lerpValue(fetchPigment(i0 + ivec3(0, 1, 1)), fetchPigment(i0 + ivec3(1, 1, 1)), f.x);
    return lerpValue(lerpValue(c00, c10, f.y), lerpValue(c01, c11, f.y), f.z);
}

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(q, cellCount()))) return;
    float fade = exp(-params.rates.x * timeStep());
    pigmentOut[cellElement(q)] = flushTiny(samplePigment(backTrace(cellCentre(q))) * fade);
}
