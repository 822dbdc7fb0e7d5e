// applyBuoyancy on the sparse grid: v += dt * buoyancy * mean pigment alpha of the two cells
// beside each stored y face of the listed bricks (docs/fluid.md, "Sparse domain": a cell that is
// not stored has no pigment); solid faces keep the solid's velocity. The dense stage's formula (apply_buoyancy.comp).
// Twin: fluid/reference/apply_buoyancy.cpp with the reference's active cells.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_solids.glsl"

layout(std430, binding = 3) readonly buffer VelocityY {
    float velocityY[];
};
layout(std430, binding = 4) readonly buffer Pigment {
    vec4 pigment[];
};
layout(std430, binding = 5) writeonly buffer Out {
    float outValues[];
};

float alphaAt(ivec3 q) {
    int e = cellElementAt(resolveCell(q));
    return e < 0 ? 0.0 : pigment[e].a;
}

void buoyFace(BrickCell at, ivec3 l) {
    ivec3 q = at.brick * kBrick + l;
    int element = faceElementIn(at.slot, 1, l);
    float v = velocityY[element];
    if (!wallNormalFace(1, q) && !sparseSolidFace(1, q)) {
        float density = 0.5 * (alphaAt(q - ivec3(0, 1, 0)) + alphaAt(q));
        v += timeStep() * params.rates.y * density;
    }
    outValues[element] = v;
}

void main() {
    BrickCell at = listedCell();
    buoyFace(at, at.local);
    if (at.local.y == kBrick - 1) buoyFace(at, at.local + ivec3(0, 1, 0));
}
