// advectVelocity on the sparse grid: every stored face of one component (kTarget) of the listed
// bricks takes its value semi-Lagrangian advected through the velocity as it was on entry, then
// the drag (docs/fluid.md, steps 2 and "Sparse domain"; Stam 1999, eq. 7). The dense stage's
// formula (advect_velocity.comp) over the virtual domain, a face that is not stored reading as 0.
// Solid faces keep the solid's velocity (sparse_solids.glsl). Twin:
// fluid/reference/advect_velocity.cpp with the reference's active cells.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_solids.glsl"

layout(std430, binding = 3) readonly buffer VelocityX {
    float velocityX[];
};
layout(std430, binding = 4) readonly buffer VelocityY {
    float velocityY[];
};
layout(std430, binding = 5) readonly buffer VelocityZ {
    float velocityZ[];
};
layout(std430, binding = 6) writeonly buffer Out {
    float outValues[];
};

float loadFaceField(int field, int c, ivec3 index) {
    int e = faceElementAt(c, index);
    if (e < 0) return 0.0;
    return c == 0 ? velocityX[e] : (c == 1 ? velocityY[e] : velocityZ[e]);
}

#include "fluid_sampling.glsl"

void advectFace(BrickCell at, int c, ivec3 l) {
    ivec3 q = at.brick * kBrick + l;
    int element = faceElementIn(at.slot, c, l);
    if (sparseSolidFace(c, q)) { // solid faces move with the solid, not with the air
        outValues[element] = c == 0 ? velocityX[element] : (c == 1 ? velocityY[element] : velocityZ[element]);
        return;
    }
    float value = 0.0;
    if (!wallNormalFace(c, q)) {
        value = sampleFace(kVelocityField, c, backTraceFromFace(c, q, timeStep()));
        value *= exp(-params.cell.w * timeStep());
    }
    outValues[element] = flushTiny(value);
}

void main() {
    BrickCell at = listedCell();
    int c = int(kTarget);
    advectFace(at, c, at.local);
    if (at.local[c] == kBrick - 1) { // the brick's top layer of faces along c
        ivec3 top = at.local;
        top[c] = kBrick;
        advectFace(at, c, top);
    }
}
