// applyTurbulence's second pass: u_c += dt * amplitude * (curl psi)_c on every face of component c
// (kTarget) but the wall-normal ones (unchanged) and, with solids, the solid ones (they keep the
// solid's velocity); psi is curl_noise.glsl's potential at the step's time, which
// turbulence_potential.comp wrote on every edge (docs/fluid.md, "applyTurbulence"). The curl by
// the grid's differences: u_x = (psi_z(j+1) - psi_z(j) - psi_y(k+1) + psi_y(k)) / h, cyclically. Twin: fluid/reference/apply_turbulence.cpp. Writes every face of the
// component to a buffer that the solver copies into the image, or with kDirectStore into the image
// itself (each invocation reads only the face it writes).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#include "fluid_solids.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocity;
layout(std430, binding = 2) writeonly buffer Out {
    float outValues[];
};
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform writeonly image3D outField; // kDirectStore
layout(std430, binding = 4) readonly buffer Potential {
    vec4 potential[]; // by grid corner, x-fastest: xyz the potential on the edges from it
};

float edgePotential(int c, ivec3 e) {
    ivec3 corners = cellCount() + ivec3(1);
    return potential[e.x + corners.x * (e.y + corners.y * e.z)][c];
}

float curlNoiseFace(int c, ivec3 q) {
    int a = (c + 1) % 3, b = (c + 2) % 3;
    ivec3 da = ivec3(0), db = ivec3(0);
    da[a] = 1;
    db[b] = 1;
    return ((edgePotential(b, q + da) - edgePotential(b, q)) -
            (edgePotential(a, q + db) - edgePotential(a, q))) *
           inverseCellSize();
}

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
