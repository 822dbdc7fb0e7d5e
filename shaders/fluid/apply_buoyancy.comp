// applyBuoyancy: v += dt * buoyancy * mean pigment alpha of the two cells beside the face
// (docs/fluid.md). Twin: fluid/reference/apply_buoyancy.cpp. Writes every y face (unchanged on
// walls) to a buffer that the solver copies into the image, or with kDirectStore into the image
// itself (each invocation reads only the face it writes).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#include "fluid_solids.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityY;
layout(binding = 2, MFX_PIGMENT_FORMAT) uniform readonly image3D pigment;
layout(std430, binding = 3) writeonly buffer Out {
    float outValues[];
};
layout(binding = 4, MFX_VELOCITY_FORMAT) uniform writeonly image3D outField; // kDirectStore

void main() {
    ivec3 q = stageInvocation();
    if (any(greaterThanEqual(q, faceCount(1)))) return;
    float v = imageLoad(velocityY, q).r;
    if (!wallNormalFace(1, q) && !(solidsNearWorkgroup() && solidFace(1, q))) { // solid faces keep the solid's velocity
        float density = 0.5 * (imageLoad(pigment, resolveCell(q - ivec3(0, 1, 0))).a +
                               imageLoad(pigment, resolveCell(q)).a);
        v += timeStep() * params.rates.y * density;
    }
    if (kDirectStore)
        imageStore(outField, q, vec4(MFX_STORED(v)));
    else
        outValues[faceElement(1, q)] = v;
}
