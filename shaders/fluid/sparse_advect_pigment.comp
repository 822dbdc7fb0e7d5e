// advectPigment on the sparse grid: the RGBA pigment of every cell of the listed bricks,
// semi-Lagrangian advected, then faded (docs/fluid.md, step 3 and "Sparse domain"); a cell that is
// not stored reads as 0, no pigment. The dense stage's formula (advect_pigment.comp).
// Twin: fluid/reference/advect_pigment.cpp with the reference's active cells.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_common.glsl"

layout(std430, binding = 3) readonly buffer VelocityX {
    float velocityX[];
};
layout(std430, binding = 4) readonly buffer VelocityY {
    float velocityY[];
};
layout(std430, binding = 5) readonly buffer VelocityZ {
    float velocityZ[];
};
layout(std430, binding = 6) readonly buffer PigmentIn {
    vec4 pigmentIn[];
};
layout(std430, binding = 7) writeonly buffer PigmentOut {
    vec4 pigmentOut[];
};

float loadFaceField(int field, int c, ivec3 index) {
    int e = faceElementAt(c, index);
    if (e < 0) return 0.0;
    return c == 0 ? velocityX[e] : (c == 1 ? velocityY[e] : velocityZ[e]);
}

#include "fluid_sampling.glsl"

vec4 fetchPigment(ivec3 index) {
    int e = cellElementAt(resolveCell(index));
    return e < 0 ? vec4(0.0) : pigmentIn[e];
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
    BrickCell at = listedCell();
    ivec3 q = at.brick * kBrick + at.local;
    vec4 value = samplePigment(backTraceFromCell(q, timeStep()));
    pigmentOut[cellElementIn(at.slot, at.local)] =
        flushTiny(value * exp(-params.rates.x * timeStep()));
}
