// Trilinear sampling and back-tracing through the velocity field. The including shader first
// defines `float loadVelocity(int c, ivec3 faceIndex)`, a plain load of an in-range face of the
// velocity it advects with.
#ifndef MFX_FLUID_SAMPLING_GLSL
#define MFX_FLUID_SAMPLING_GLSL

// One corner of the trilinear stencil: load, then the mirrors of x, y and z in that order (the
// reference's order).
float cornerValue(int c, AxisRef x, AxisRef y, AxisRef z) {
    float v = loadVelocity(c, ivec3(x.index, y.index, z.index));
    v = x.scale * v + x.offset;
    v = y.scale * v + y.offset;
    return z.scale * v + z.offset;
}

float sampleVelocity(int c, vec3 x) {
    vec3 g = gridCoordinate(x, faceOffset(c));
    vec3 base = floor(g);
    vec3 f = g - base;
    ivec3 i0 = ivec3(base);
    ivec3 n = faceCount(c);
    // Each axis resolved once for its two stencil indices instead of once per corner.
    AxisRef x0 = resolveAxis(c, 0, n.x, i0.x), x1 = resolveAxis(c, 0, n.x, i0.x + 1);
    AxisRef y0 = resolveAxis(c, 1, n.y, i0.y), y1 = resolveAxis(c, 1, n.y, i0.y + 1);
    AxisRef z0 = resolveAxis(c, 2, n.z, i0.z), z1 = resolveAxis(c, 2, n.z, i0.z + 1);
    float c00 = lerpValue(cornerValue(c, x0, y0, z0), cornerValue(c, x1, y0, z0), f.x);
    float c10 = lerpValue(cornerValue(c, x0, y1, z0), cornerValue(c, x1, y1, z0), f.x);
    float c01 = lerpValue(cornerValue(c, x0, y0, z1), cornerValue(c, x1, y0, z1), f.x);
    float c11 = lerpValue(cornerValue(c, x0, y1, z1), cornerValue(c, x1, y1, z1), f.x);
    return lerpValue(lerpValue(c00, c10, f.y), lerpValue(c01, c11, f.y), f.z);
}

vec3 velocityAt(vec3 x) {
    return vec3(sampleVelocity(0, x), sampleVelocity(1, x), sampleVelocity(2, x));
}

vec3 backTrace(vec3 x) {
    vec3 v = velocityAt(x);
    if (kIntegrator == MFX_INTEGRATOR_EULER) return clampToDomain(x - timeStep() * v);
    vec3 mid = clampToDomain(x - 0.5 * timeStep() * v);
    return clampToDomain(x - timeStep() * velocityAt(mid));
}

#endif
