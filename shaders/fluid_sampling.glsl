// Trilinear sampling and back-tracing through the velocity field. The including shader first
// defines `float fetchVelocity(int c, ivec3 faceIndex)` (possibly out of range, resolved with
// resolveFace) for the velocity it advects with.
#ifndef MFX_FLUID_SAMPLING_GLSL
#define MFX_FLUID_SAMPLING_GLSL

float sampleVelocity(int c, vec3 x) {
    vec3 g = gridCoordinate(x, faceOffset(c));
    vec3 base = floor(g);
    vec3 f = g - base;
    ivec3 i0 = ivec3(base);
    float c00 = lerpValue(fetchVelocity(c, i0 + ivec3(0, 0, 0)),
                          fetchVelocity(c, i0 + ivec3(1, 0, 0)), f.x);
    float c10 = lerpValue(fetchVelocity(c, i0 + ivec3(0, 1, 0)),
                          fetchVelocity(c, i0 + ivec3(1, 1, 0)), f.x);
    float c01 = lerpValue(fetchVelocity(c, i0 + ivec3(0, 0, 1)),
                          fetchVelocity(c, i0 + ivec3(1, 0, 1)), f.x);
    float c11 = lerpValue(fetchVelocity(c, i0 + ivec3(0, 1, 1)),
                          fetchVelocity(c, i0 + ivec3(1, 1, 1)), f.x);
    return lerpValue(lerpValue(c00, c10, f.y), lerpValue(c01, c11, f.y), f.z);
}

vec3 velocityAt(vec3 x) {
    return vec3(sampleVelocity(0, x), sampleVelocity(1, x), sampleVelocity(2, x));
}

vec3 backTrace(vec3 x) {
    vec3 v = velocityAt(x);
    if (params.boundaryLow.w == MFX_INTEGRATOR_EULER) return clampToDomain(x - timeStep() * v);
    vec3 mid = clampToDomain(x - 0.5 * timeStep() * v);
    return clampToDomain(x - timeStep() * velocityAt(mid));
}

#endif
