// vorticityConfinement, second pass: f = epsilon h (N x omega) with N = grad|omega| /
// |grad|omega||, added to each face as dt times the mean force of the two cells beside it
// (docs/fluid.md; Fedkiw, Stam, Jensen 2001, eqs. 10-11). Twin:
// fluid/reference/vorticity_confinement.cpp.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, r32f) uniform image3D velocityX;
layout(binding = 2, r32f) uniform image3D velocityY;
layout(binding = 3, r32f) uniform image3D velocityZ;
layout(binding = 4, rgba32f) uniform readonly image3D vorticity;

vec4 fetchVorticity(ivec3 q) {
    return imageLoad(vorticity, resolveCell(q));
}

// Confinement force at cell q (already resolved into the grid).
vec3 confinementForce(ivec3 q) {
    const ivec3 ex = ivec3(1, 0, 0), ey = ivec3(0, 1, 0), ez = ivec3(0, 0, 1);
    float inv2h = 1.0 / (2.0 * cellSize());
    vec4 w = fetchVorticity(q);
    vec3 eta = vec3((fetchVorticity(q + ex).w - fetchVorticity(q - ex).w) * inv2h,
                    (fetchVorticity(q + ey).w - fetchVorticity(q - ey).w) * inv2h,
                    (fetchVorticity(q + ez).w - fetchVorticity(q - ez).w) * inv2h);
    // Regularised normalisation: where |omega| barely varies there is nothing to confine.
    vec3 n = eta / (length(eta) + 1e-3 * w.w * inverseCellSize() + 1e-20);
    return params.rates.z * cellSize() * cross(n, w.xyz);
}

void main() {
    int c = int(kTarget);
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(q, faceCount(c))) || wallNormalFace(c, q)) return;
    ivec3 below = q;
    below[c] -= 1;
    float f = 0.5 * (confinementForce(resolveCell(below))[c] + confinementForce(resolveCell(q))[c]);
    if (c == 0)
        imageStore(velocityX, q, vec4(imageLoad(velocityX, q).r + timeStep() * f));
    else if (c == 1)
        imageStore(velocityY, q, vec4(imageLoad(velocityY, q).r + timeStep() * f));
    else
        imageStore(velocityZ, q, vec4(imageLoad(velocityZ, q).r + timeStep() * f));
}
