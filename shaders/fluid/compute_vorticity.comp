// vorticityConfinement, first pass: omega = curl u at cell centres, stored with |omega|
// (docs/fluid.md; Fedkiw, Stam, Jensen 2001, eq. 9). Twin:
// fluid/reference/vorticity_confinement.cpp. Writes a buffer that the solver copies into the
// vorticity image, or with kDirectStore the image itself.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityX;
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityY;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityZ;
layout(std430, binding = 4) writeonly buffer Vorticity {
    vec4 vorticity[];
};
layout(binding = 5, rgba32f) uniform writeonly image3D vorticityImage; // kDirectStore

float fetchVelocity(int c, ivec3 index) {
    FaceRef r = resolveFace(c, index);
    float raw = c == 0
                    ? imageLoad(velocityX, r.index).r
                    : (c == 1 ? imageLoad(velocityY, r.index).r : imageLoad(velocityZ, r.index).r);
    return r.scale * raw + r.offset;
}

// Cell-centred velocity component c of a possibly out-of-range cell.
float centred(int c, ivec3 q) {
    ivec3 hi = q;
    hi[c] += 1;
    return 0.5 * (fetchVelocity(c, q) + fetchVelocity(c, hi));
}

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(q, cellCount()))) return;
    const ivec3 ex = ivec3(1, 0, 0), ey = ivec3(0, 1, 0), ez = ivec3(0, 0, 1);
    float inv2h = 1.0 / (2.0 * cellSize());
    vec3 w = vec3(
        (centred(2, q + ey) - centred(2, q - ey) - centred(1, q + ez) + centred(1, q - ez)) * inv2h,
        (centred(0, q + ez) - centred(0, q - ez) - centred(2, q + ex) + centred(2, q - ex)) * inv2h,
        (centred(1, q + ex) - centred(1, q - ex) - centred(0, q + ey) + centred(0, q - ey)) *
            inv2h);
    if (kDirectStore)
        imageStore(vorticityImage, q, vec4(w, length(w)));
    else
        vorticity[cellElement(q)] = vec4(w, length(w));
}
