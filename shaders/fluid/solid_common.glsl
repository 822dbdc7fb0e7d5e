// What the dense and the sparse grids' solids share (docs/fluid.md, "Solids"): the capsule tests
// of markSolids (shaders/fluid/mark_solids.comp, sparse_mark_solids.comp) and the trilinear sample
// from the fluid cells alone (advect_pigment.comp, sparse_advect_pigment.comp). Twin:
// fluid/reference/mark_solids.cpp (axisParameter, inside, solidVelocityAt,
// sampleCellOutsideSolids).
#ifndef MFX_SOLID_COMMON_GLSL
#define MFX_SOLID_COMMON_GLSL

// Where the point of the axis closest to x lies along it: 0 at end A, 1 at end B.
float axisParameter(FluidSolid s, vec3 x) {
    vec3 ab = s.endB.xyz - s.endA.xyz;
    float length2 = dot(ab, ab);
    return length2 > 0.0 ? clamp(dot(x - s.endA.xyz, ab) / length2, 0.0, 1.0) : 0.0;
}

bool insideSolid(FluidSolid s, vec3 x) {
    vec3 closest = mix(s.endA.xyz, s.endB.xyz, axisParameter(s, x));
    vec3 d = x - closest;
    return dot(d, d) < s.endA.w * s.endA.w;
}

// Component c of the solid's velocity at x (its ends' velocities blended along the axis).
float solidVelocityAt(FluidSolid s, vec3 x, int c) {
    return mix(s.velocityA.xyz, s.velocityB.xyz, axisParameter(s, x))[c];
}

// The trilinear sample from the fluid cells alone, the weights of solid cells dropped and the
// rest renormalised (0 when all eight are solid), in the reference's order
// (sampleCellOutsideSolids), from the eight corner values a plain sample reads (corner k at
// i0 + (k & 1, (k >> 1) & 1, k >> 2)), the fractions f and the stencil's solid corners (`solid`,
// corner k at bit k).
vec4 sampleOutsideSolids(vec3 f, vec4 corners[8], uint solid) {
    vec4 sum = vec4(0.0);
    float weight = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        if ((solid & (1u << uint(corner))) != 0u) continue;
        ivec3 d = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        float w = (d.x != 0 ? f.x : 1.0 - f.x) * (d.y != 0 ? f.y : 1.0 - f.y) *
                  (d.z != 0 ? f.z : 1.0 - f.z);
        sum += w * corners[corner];
        weight += w;
    }
    return weight > 0.0 ? sum / weight : vec4(0.0);
}

#endif
