// Trilinear sampling of face fields and back-tracing through the velocity field. The including
// shader first defines `float loadFaceField(int field, int c, ivec3 faceIndex)`, a plain load of
// an in-range face of component c of one of its face fields, field kVelocityField being the
// velocity every trace follows.
#ifndef MFX_FLUID_SAMPLING_GLSL
#define MFX_FLUID_SAMPLING_GLSL

const int kVelocityField = 0;

// One corner of the trilinear stencil: load, then the mirrors of x, y and z in that order (the
// reference's order).
float cornerValue(int field, int c, AxisRef x, AxisRef y, AxisRef z) {
    float v = loadFaceField(field, c, ivec3(x.index, y.index, z.index));
    v = x.scale * v + x.offset;
    v = y.scale * v + y.offset;
    return z.scale * v + z.offset;
}

// The trilinear stencil of component c's faces around x: each axis resolved once for its two
// indices instead of once per corner, and the weights.
struct FaceStencil {
    AxisRef x0, x1, y0, y1, z0, z1;
    vec3 f;
};

FaceStencil faceStencil(int c, vec3 x) {
    vec3 g = gridCoordinate(x, faceOffset(c));
    vec3 base = floor(g);
    ivec3 i0 = ivec3(base);
    ivec3 n = faceCount(c);
    FaceStencil s;
    s.x0 = resolveAxis(c, 0, n.x, i0.x);
    s.x1 = resolveAxis(c, 0, n.x, i0.x + 1);
    s.y0 = resolveAxis(c, 1, n.y, i0.y);
    s.y1 = resolveAxis(c, 1, n.y, i0.y + 1);
    s.z0 = resolveAxis(c, 2, n.z, i0.z);
    s.z1 = resolveAxis(c, 2, n.z, i0.z + 1);
    s.f = g - base;
    return s;
}

float sampleFace(int field, int c, vec3 x) {
    FaceStencil s = faceStencil(c, x);
    float c00 = lerpValue(cornerValue(field, c, s.x0, s.y0, s.z0),
                          cornerValue(field, c, s.x1, s.y0, s.z0), s.f.x);
    float c10 = lerpValue(cornerValue(field, c, s.x0, s.y1, s.z0),
                          cornerValue(field, c, s.x1, s.y1, s.z0), s.f.x);
    float c01 = lerpValue(cornerValue(field, c, s.x0, s.y0, s.z1),
                          cornerValue(field, c, s.x1, s.y0, s.z1), s.f.x);
    float c11 = lerpValue(cornerValue(field, c, s.x0, s.y1, s.z1),
                          cornerValue(field, c, s.x1, s.y1, s.z1), s.f.x);
    return lerpValue(lerpValue(c00, c10, s.f.y), lerpValue(c01, c11, s.f.y), s.f.z);
}

// The smallest and largest of the eight values sampleFace(field, c, x) interpolates (the limiter
// of MacCormack and BFECC; fluid/reference/semi_lagrangian.cpp).
vec2 faceRange(int field, int c, vec3 x) {
    FaceStencil s = faceStencil(c, x);
    vec2 range = vec2(cornerValue(field, c, s.x0, s.y0, s.z0));
    for (int corner = 1; corner < 8; ++corner) {
        float v = cornerValue(field, c, (corner & 1) != 0 ? s.x1 : s.x0,
                              (corner & 2) != 0 ? s.y1 : s.y0, (corner & 4) != 0 ? s.z1 : s.z0);
        range = vec2(min(range.x, v), max(range.y, v));
    }
    return range;
}

float sampleVelocity(int c, vec3 x) {
    return sampleFace(kVelocityField, c, x);
}

vec3 velocityAt(vec3 x) {
    return vec3(sampleVelocity(0, x), sampleVelocity(1, x), sampleVelocity(2, x));
}

// Where the point at x came from `interval` seconds ago (a negative interval traces forwards).
vec3 backTrace(vec3 x, float interval) {
    vec3 v = velocityAt(x);
    if (kIntegrator == MFX_INTEGRATOR_EULER) return clampToDomain(x - interval * v);
    vec3 mid = clampToDomain(x - 0.5 * interval * v);
    return clampToDomain(x - interval * velocityAt(mid));
}

vec3 backTrace(vec3 x) {
    return backTrace(x, timeStep());
}

#endif
