// applyTurbulence's first pass: the curl noise's potential on every edge of the grid, once
// (curl_noise.glsl edgePotential), for the faces to difference (apply_turbulence.comp reads each
// edge's value four times, for the four faces around it). One invocation per grid corner e in
// [0, n]^3: the potential's x, y and z components on the edges along x, y and z from e (0 where
// that edge leaves the grid), as one vec4, x-fastest. Twin: fluid/reference/apply_turbulence.cpp.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "curl_noise.glsl"

layout(std430, binding = 1) writeonly buffer Potential {
    vec4 potential[];
};

void main() {
    ivec3 e = ivec3(gl_GlobalInvocationID);
    ivec3 corners = cellCount() + ivec3(1);
    if (any(greaterThanEqual(e, corners))) return;
    vec4 p = vec4(0.0);
    for (int c = 0; c < 3; ++c)
        if (e[c] < corners[c] - 1) p[c] = edgePotential(c, e);
    potential[e.x + corners.x * (e.y + corners.y * e.z)] = p;
}
