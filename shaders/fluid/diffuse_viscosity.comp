// diffuseViscosity: one Jacobi sweep of the implicit diffusion (I - nu dt Laplacian) x = u,
// x <- (u + alpha * sum of 6 neighbours of x) / (1 + 6 alpha) (docs/fluid.md; Stam 1999, sec. 3).
// Twin: fluid/reference/diffuse_viscosity.cpp. One dispatch per component and sweep.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#include "fluid_solids.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D sourceX;
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform readonly image3D sourceY;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform readonly image3D sourceZ;
layout(binding = 4, MFX_VELOCITY_FORMAT) uniform readonly image3D guessX;
layout(binding = 5, MFX_VELOCITY_FORMAT) uniform readonly image3D guessY;
layout(binding = 6, MFX_VELOCITY_FORMAT) uniform readonly image3D guessZ;
layout(binding = 7, MFX_VELOCITY_FORMAT) uniform writeonly image3D outX;
layout(binding = 8, MFX_VELOCITY_FORMAT) uniform writeonly image3D outY;
layout(binding = 9, MFX_VELOCITY_FORMAT) uniform writeonly image3D outZ;

float fetchGuess(int c, ivec3 index) {
    FaceRef r = resolveFace(c, index);
    float raw = c == 0 ? imageLoad(guessX, r.index).r
                       : (c == 1 ? imageLoad(guessY, r.index).r : imageLoad(guessZ, r.index).r);
    return r.scale * raw + r.offset;
}

void main() {
    int c = int(kTarget);
    ivec3 q = stageInvocation();
    if (any(greaterThanEqual(q, faceCount(c)))) return;
    float value = 0.0;
    if (solidsNearWorkgroup() && solidFace(c, q)) { // the solid's velocity, a fixed boundary value
        value = c == 0 ? imageLoad(sourceX, q).r
                       : (c == 1 ? imageLoad(sourceY, q).r : imageLoad(sourceZ, q).r);
    } else if (!wallNormalFace(c, q)) {
        float alpha = params.rates.w;
        float source = c == 0 ? imageLoad(sourceX, q).r
                              : (c == 1 ? imageLoad(sourceY, q).r : imageLoad(sourceZ, q).r);
        float sum = fetchGuess(c, q + ivec3(1, 0, 0)) + fetchGuess(c, q + ivec3(-1, 0, 0)) +
                    fetchGuess(c, q + ivec3(0, 1, 0)) + fetchGuess(c, q + ivec3(0, -1, 0)) +
                    fetchGuess(c, q + ivec3(0, 0, 1)) + fetchGuess(c, q + ivec3(0, 0, -1));
        value = (source + alpha * sum) / (1.0 + 6.0 * alpha);
    }
    if (c == 0)
        imageStore(outX, q, vec4(MFX_STORED(value)));
    else if (c == 1)
        imageStore(outY, q, vec4(MFX_STORED(value)));
    else
        imageStore(outZ, q, vec4(MFX_STORED(value)));
}
