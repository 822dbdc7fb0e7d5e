// Grid access of the smoke solver, shared by its compute shaders: the same index, fetch and
// sampling rules as fluid/reference/grid_access.cpp (docs/fluid.md, "Grid access").
#ifndef MFX_FLUID_COMMON_GLSL
#define MFX_FLUID_COMMON_GLSL

#include "shared/fluid.h"

#include "field_formats.glsl"

// The workgroup shape is given by specialization (SolverOptions::workgroup; constant ids 8-10),
// the defaults being the shared header's.
layout(local_size_x_id = 8, local_size_y_id = 9, local_size_z_id = 10) in;

layout(std140, binding = 0) uniform Parameters {
    FluidParameters params;
};
layout(push_constant) uniform Dispatch {
    FluidDispatch dispatchInfo;
};

// The field a pipeline works on (MFX_TARGET_*), fixed per pipeline by specialization: with the
// component a constant, every index by component folds away (a CPU driver would otherwise
// scalarise each dynamically indexed vector access lane by lane).
layout(constant_id = 0) const uint kTarget = 0;

// Advection writes a value of magnitude below kFlushBelow as 0 (docs/fluid.md, steps 2 and 3):
// the decaying tails of faded pigment and dragged velocity would otherwise pass through float
// denormals, which a CPU driver computes many times slower than normal numbers.
const float kFlushBelow = 1.0e-30;
float flushTiny(float v) {
    return abs(v) < kFlushBelow ? 0.0 : v;
}
vec4 flushTiny(vec4 v) {
    return mix(v, vec4(0.0), lessThan(abs(v), vec4(kFlushBelow)));
}

ivec3 cellCount() {
    return ivec3(params.size.xyz);
}
float cellSize() {
    return params.cell.x;
}
float inverseCellSize() {
    return params.cell.y;
}
float timeStep() {
    return params.cell.z;
}

// Boundary kinds and the integrator are fixed for a solver's life and given by specialization
// (the same values as FluidParameters.boundaryLow/High): every boundary test then folds to a
// constant instead of a uniform load and a select per lane.
layout(constant_id = 1) const uint kBoundaryLowX = 0;
layout(constant_id = 2) const uint kBoundaryHighX = 0;
layout(constant_id = 3) const uint kBoundaryLowY = 0;
layout(constant_id = 4) const uint kBoundaryHighY = 0;
layout(constant_id = 5) const uint kBoundaryLowZ = 0;
layout(constant_id = 6) const uint kBoundaryHighZ = 0;
layout(constant_id = 7) const uint kIntegrator = MFX_INTEGRATOR_EULER;

uint boundaryKind(int axis, bool high) {
    uint low = axis == 0 ? kBoundaryLowX : (axis == 1 ? kBoundaryLowY : kBoundaryLowZ);
    uint top = axis == 0 ? kBoundaryHighX : (axis == 1 ? kBoundaryHighY : kBoundaryHighZ);
    return high ? top : low;
}
bool periodicAxis(int axis) {
    return boundaryKind(axis, false) == MFX_BOUNDARY_PERIODIC;
}
bool isWall(uint kind) {
    return kind == MFX_BOUNDARY_WALL_FREE_SLIP || kind == MFX_BOUNDARY_WALL_NO_SLIP;
}

ivec3 faceCount(int c) {
    ivec3 n = cellCount();
    n[c] += 1;
    return n;
}

// i mod n for -n <= i < 3n (callers are at most one cell outside a face array), without an
// integer division, which a CPU driver's SIMD code would do lane by lane.
int wrapIndex(int i, int n) {
    i = i < 0 ? i + n : i;
    i = i >= n ? i - n : i;
    return i >= n ? i - n : i; // a one-cell axis can be two periods out (face n + 1)
}
float lerpValue(float a, float b, float t) {
    return a + t * (b - a);
}
vec4 lerpValue(vec4 a, vec4 b, float t) {
    return a + t * (b - a);
}

// A face fetch resolved: value = scale * field[index] + offset (a no-slip wall mirrors the
// tangential component about the wall velocity: 2 w - u).
struct FaceRef {
    ivec3 index;
    float scale;
    float offset;
};

// Resolves one axis of a face index (see resolveFace): wrap, or clamp and possibly mirror.
// Written without branches: a CPU driver runs both sides of every branch under a lane mask, so
// straight-line selects are cheaper than ifs here.
void resolveFaceAxis(int c, int a, int n, inout int i, inout FaceRef ref) {
    bool periodic = periodicAxis(a);
    bool high = i >= n;
    bool outside = !periodic && (i < 0 || high);
    bool mirror = outside && c != a && boundaryKind(a, high) == MFX_BOUNDARY_WALL_NO_SLIP;
    float wall = params.wallVelocity[2 * a + (high ? 1 : 0)][c];
    i = periodic ? wrapIndex(i, cellCount()[a]) : clamp(i, 0, n - 1);
    ref.scale = mirror ? -ref.scale : ref.scale;
    ref.offset = mirror ? 2.0 * wall - ref.offset : ref.offset;
}

// One axis of a face index resolved on its own: the index to load, and the affine map
// v -> scale * v + offset that the axis's mirror (if any) applies.
struct AxisRef {
    int index;
    float scale;
    float offset;
};

AxisRef resolveAxis(int c, int a, int n, int i) {
    FaceRef ref;
    ref.scale = 1.0;
    ref.offset = 0.0;
    resolveFaceAxis(c, a, n, i, ref);
    return AxisRef(i, ref.scale, ref.offset);
}

FaceRef resolveFace(int c, ivec3 index) {
    ivec3 n = faceCount(c);
    FaceRef ref;
    ref.scale = 1.0;
    ref.offset = 0.0;
    // Axes in the order x, y, z, as the reference composes its mirrors.
    resolveFaceAxis(c, 0, n.x, index.x, ref);
    resolveFaceAxis(c, 1, n.y, index.y, ref);
    resolveFaceAxis(c, 2, n.z, index.z, ref);
    ref.index = index;
    return ref;
}

ivec3 resolveCell(ivec3 index) {
    for (int a = 0; a < 3; ++a)
        index[a] = periodicAxis(a) ? wrapIndex(index[a], cellCount()[a])
                                   : clamp(index[a], 0, cellCount()[a] - 1);
    return index;
}

bool wallNormalFace(int c, ivec3 index) {
    return (index[c] == 0 && isWall(boundaryKind(c, false))) ||
           (index[c] == cellCount()[c] && isWall(boundaryKind(c, true)));
}

// The store path of the stages that write a whole field (SolverOptions::storePath; docs/fluid.md,
// "Grid"). false: into a storage buffer holding one value per cell or per face of component c,
// x-fastest (the layout of a FieldState, and of a buffer-to-image copy), which the solver then
// copies into the field's image: on a CPU driver (lavapipe) an image store runs a costly per-lane
// loop, a buffer store a cheap one, and the copy is a plain memory copy. true: straight into the
// field's image (a GPU, where the copy would move every byte twice more). Either way the field is
// read from its image, and each such stage binds both its buffer and its image.
layout(constant_id = 14) const bool kDirectStore = false;

// Element of an in-range cell or face in such a buffer.
int cellElement(ivec3 q) {
    ivec3 n = cellCount();
    return q.x + n.x * (q.y + n.y * q.z);
}
int faceElement(int c, ivec3 q) {
    ivec3 n = faceCount(c);
    return q.x + n.x * (q.y + n.y * q.z);
}

vec3 facePosition(int c, ivec3 index) {
    vec3 x = (vec3(index) + 0.5) * cellSize();
    x[c] -= 0.5 * cellSize();
    return x;
}

vec3 cellCentre(ivec3 index) {
    return (vec3(index) + 0.5) * cellSize();
}

vec3 clampToDomain(vec3 x) {
    for (int a = 0; a < 3; ++a) {
        float len = float(cellCount()[a]) * cellSize();
        x[a] = periodicAxis(a) ? x[a] - len * floor(x[a] / len) : clamp(x[a], 0.0, len);
    }
    return x;
}

// Grid coordinate of world position x for a field whose samples sit at `offset` cells.
vec3 gridCoordinate(vec3 x, vec3 offset) {
    return x * inverseCellSize() - offset;
}

vec3 faceOffset(int c) {
    vec3 o = vec3(0.5);
    o[c] = 0.0;
    return o;
}

#endif
