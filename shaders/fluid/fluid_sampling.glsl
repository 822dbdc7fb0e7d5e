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

// Velocity at grid points. At a face or a cell centre the trilinear stencil of each component
// has weight 0 along some axes (a + 0 (b - a) = a: only the near corner counts) and 1/2 along the
// others, so only the corners with a nonzero weight are loaded: the same values as velocityAt
// there, from 1 to 4 loads a component instead of 8.

// One z-slice of sampleFaceHalfway: the corner at (x0, y0), averaged with x1 and y1 where
// `between`.
float halfwayXY(int field, int d, AxisRef x0, AxisRef x1, AxisRef y0, AxisRef y1, AxisRef z,
                bvec2 between) {
    float a = cornerValue(field, d, x0, y0, z);
    if (between.x) a = lerpValue(a, cornerValue(field, d, x1, y0, z), 0.5);
    if (!between.y) return a;
    float b = cornerValue(field, d, x0, y1, z);
    if (between.x) b = lerpValue(b, cornerValue(field, d, x1, y1, z), 0.5);
    return lerpValue(a, b, 0.5);
}

// Component d's faces sampled at the point of its face grid i0 + between / 2 (between: 0 or 1 an
// axis).
float sampleFaceHalfway(int field, int d, ivec3 i0, bvec3 between) {
    ivec3 n = faceCount(d);
    AxisRef x0 = resolveAxis(d, 0, n.x, i0.x), x1 = resolveAxis(d, 0, n.x, i0.x + 1);
    AxisRef y0 = resolveAxis(d, 1, n.y, i0.y), y1 = resolveAxis(d, 1, n.y, i0.y + 1);
    AxisRef z0 = resolveAxis(d, 2, n.z, i0.z), z1 = resolveAxis(d, 2, n.z, i0.z + 1);
    float low = halfwayXY(field, d, x0, x1, y0, y1, z0, between.xy);
    if (!between.z) return low;
    return lerpValue(low, halfwayXY(field, d, x0, x1, y0, y1, z1, between.xy), 0.5);
}

// Component d of the velocity at face q of component c: face q itself when d == c; else, in d's
// face grid, the point q - e_c / 2 + e_d / 2 (halfway along axes c and d, on a grid plane along
// the third).
float velocityComponentAtFace(int d, int c, ivec3 q) {
    if (d == c) return sampleFaceHalfway(kVelocityField, d, q, bvec3(false));
    ivec3 i0 = q;
    i0[c] -= 1;
    bvec3 between = bvec3(false);
    between[c] = true;
    between[d] = true;
    return sampleFaceHalfway(kVelocityField, d, i0, between);
}

vec3 velocityAtFace(int c, ivec3 q) {
    return vec3(velocityComponentAtFace(0, c, q), velocityComponentAtFace(1, c, q),
                velocityComponentAtFace(2, c, q));
}

// The velocity at the centre of cell q: component d halfway between faces q and q + e_d.
vec3 velocityAtCell(ivec3 q) {
    return vec3(sampleFaceHalfway(kVelocityField, 0, q, bvec3(true, false, false)),
                sampleFaceHalfway(kVelocityField, 1, q, bvec3(false, true, false)),
                sampleFaceHalfway(kVelocityField, 2, q, bvec3(false, false, true)));
}

// Where the point at x, moving at v there, came from `interval` seconds ago (a negative interval
// traces forwards).
vec3 backTraceFrom(vec3 x, vec3 v, float interval) {
    if (kIntegrator == MFX_INTEGRATOR_EULER) return clampToDomain(x - interval * v);
    vec3 mid = clampToDomain(x - 0.5 * interval * v);
    return clampToDomain(x - interval * velocityAt(mid));
}

// The same from face q of component c, and from the centre of cell q.
vec3 backTraceFromFace(int c, ivec3 q, float interval) {
    return backTraceFrom(facePosition(c, q), velocityAtFace(c, q), interval);
}
vec3 backTraceFromCell(ivec3 q, float interval) {
    return backTraceFrom(cellCentre(q), velocityAtCell(q), interval);
}

#endif
