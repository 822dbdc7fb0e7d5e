// applyBuoyancy: v += dt * buoyancy * mean pigment alpha of the two cells beside the face
// (docs/fluid.md). Twin: fluid/reference/apply_buoyancy.cpp.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, r32f) uniform image3D velocityY;
layout(binding = 2, rgba32f) uniform readonly image3D pigment;

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(q, faceCount(1))) || wallNormalFace(1, q)) return;
    float density = 0.5 * (imageLoad(pigment, resolveCell(q - ivec3(0, 1, 0))).a +
                           imageLoad(pigment, resolveCell(q)).a);
    float v = imageLoad(velocityY, q).r + timeStep() * params.rates.y * density;
    imageStore(velocityY, q, vec4(v));
}
