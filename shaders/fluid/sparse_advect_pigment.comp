// advectPigment on the sparse grid: the RGBA pigment of every cell of the listed bricks,
// semi-Lagrangian advected, then faded (docs/fluid.md, step 3 and "Sparse domain"); a cell that is
// not stored reads as 0, no pigment; a solid cell holds none, and a sample beside solids is taken
// from the fluid cells alone. The dense stage's formula (advect_pigment.comp).
// Twin: fluid/reference/advect_pigment.cpp with the reference's active cells.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_solids.glsl"
#include "solid_common.glsl"

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

// The trilinear sample of the pigment at x; with solids, from the fluid cells alone where a corner
// is solid (solid_common.glsl), as the dense stage.
vec4 samplePigment(vec3 x) {
    vec3 g = gridCoordinate(x, vec3(0.5));
    vec3 base = floor(g);
    vec3 f = g - base;
    ivec3 i0 = ivec3(base);
    vec4 corners[8]; // x fastest: corner k is i0 + (k & 1, (k >> 1) & 1, k >> 2)
    uint solid = 0u; // corner k at bit k
    for (int corner = 0; corner < 8; ++corner) {
        int e = cellElementAt(resolveCell(i0 + ivec3(corner & 1, (corner >> 1) & 1, corner >> 2)));
        corners[corner] = e < 0 ? vec4(0.0) : pigmentIn[e];
        if (solidElement(e)) solid |= 1u << uint(corner);
    }
    if (solid != 0u) return sampleOutsideSolids(f, corners, solid);
    vec4 c00 = lerpValue(corners[0], corners[1], f.x);
    vec4 c10 = lerpValue(corners[2], corners[3], f.x);
    vec4 c01 = lerpValue(corners[4], corners[5], f.x);
    vec4 c11 = lerpValue(corners[6], corners[7], f.x);
    return lerpValue(lerpValue(c00, c10, f.y), lerpValue(c01, c11, f.y), f.z);
}

void main() {
    BrickCell at = listedCell();
    ivec3 q = at.brick * kBrick + at.local;
    vec4 value = samplePigment(backTraceFromCell(q, timeStep()));
    int e = cellElementIn(at.slot, at.local);
    // None inside a solid (docs/fluid.md, "Solids").
    pigmentOut[e] = solidElement(e) ? vec4(0.0) : flushTiny(value * exp(-params.rates.x * timeStep()));
}
