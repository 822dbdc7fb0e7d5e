// applyTurbulence: u_c += dt * amplitude * (curl psi)_c on every face of component c (kTarget)
// but the wall-normal ones (unchanged) and, with solids, the solid ones (they keep the solid's
// velocity); psi is curl_noise.glsl's potential at the step's time (docs/fluid.md,
// "applyTurbulence"). Twin: fluid/reference/apply_turbulence.cpp. Writes every face of the
// component to a buffer that the solver copies into the image, or with kDirectStore into the image
// itself (each invocation reads only the face it writes).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "curl_noise.glsl"
#include "fluid_solids.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocity;
layout(std430, binding = 2) writeonly buffer Out {
    float outValues[];
};
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform writeonly image3D outField; // kDirectStore

void main() {
    const int c = int(kTarget);
    ivec3 q = stageInvocation();
    if (any(greaterThanEqual(q, faceCount(c)))) return;
    float u = imageLoad(velocity, q).r;
    if (!wallNormalFace(c, q) && !(solidsNearWorkgroup() && solidFace(c, q)))
        u += timeStep() * params.turbulence.x * curlNoiseFace(c, q);
    if (kDirectStore)
        imageStore(outField, q, vec4(MFX_STORED(u)));
    else
        outValues[faceElement(c, q)] = u;
}
