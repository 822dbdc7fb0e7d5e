// vorticityConfinement, second pass: the confinement force f = epsilon h (N x omega) with
// N = grad|omega| / |grad|omega|| at every cell centre, stored once per cell for the faces on
// either side (docs/fluid.md; Fedkiw, Stam, Jensen 2001, eqs. 10-11). Twin:
// fluid/reference/vorticity_confinement.cpp. Writes a buffer that the solver copies into the force
// image, or with kDirectStore the image itself.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, rgba32f) uniform readonly image3D vorticity;
layout(std430, binding = 2) writeonly buffer Force {
    vec4 force[];
};
layout(binding = 3, rgba32f) uniform writeonly image3D forceImage; // kDirectStore

vec4 fetchVorticity(ivec3 q) {
    return imageLoad(vorticity, resolveCell(q));
}

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(q, cellCount()))) return;
    const ivec3 ex = ivec3(1, 0, 0), ey = ivec3(0, 1, 0), ez = ivec3(0, 0, 1);
    float inv2h = 1.0 / (2.0 * cellSize());
    vec4 w = fetchVorticity(q);
    vec3 eta = vec3((fetchVorticity(q + ex).w - fetchVorticity(q - ex).w) * inv2h,
                    (fetchVorticity(q + ey).w - fetchVorticity(q - ey).w) * inv2h,
                    (fetchVorticity(q + ez).w - fetchVorticity(q - ez).w) * inv2h);
    // Regularised normalisation: where |omega| barely varies there is nothing to confine.
    vec3 n = eta / (length(eta) + 1e-3 * w.w * inverseCellSize() + 1e-20);
    vec4 f = vec4(params.rates.z * cellSize() * cross(n, w.xyz), 0.0);
    if (kDirectStore)
        imageStore(forceImage, q, f);
    else
        force[cellElement(q)] = f;
}
