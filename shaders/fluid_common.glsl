// Grid access of the smoke solver, shared by its compute shaders: the same index, fetch and
// sampling rules as fluid/reference/grid_access.cpp (docs/fluid.md, "Grid access").
#ifndef MFX_FLUID_COMMON_GLSL
#define MFX_FLUID_COMMON_GLSL

#include "shared/fluid.h"

layout(local_size_x = MFX_FLUID_GROUP_X, local_size_y = MFX_FLUID_GROUP_Y,
       local_size_z = MFX_FLUID_GROUP_Z) in;

layout(std140, binding = 0) uniform Parameters {
    FluidParameters params;
};
layout(push_constant) uniform Dispatch {
    FluidDispatch dispatchInfo;
};

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

uint boundaryKind(int axis, bool high) {
    return high ? params.boundaryHigh[axis] : params.boundaryLow[axis];
}
bool periodicAxis(int axis) {
    return params.boundaryLow[axis] == MFX_BOUNDARY_PERIODIC;
}
bool isWall(uint kind) {
    return kind == MFX_BOUNDARY_WALL_FREE_SLIP || kind == MFX_BOUNDARY_WALL_NO_SLIP;
}

ivec3 faceCount(int c) {
    ivec3 n = cellCount();
    n[c] += 1;
    return n;
}

int wrapIndex(int i, int n) {
    return ((i % n) + n) % n;
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

FaceRef resolveFace(int c, ivec3 index) {
    ivec3 n = faceCount(c);
    FaceRef ref;
    ref.scale = 1.0;
    ref.offset = 0.0;
    bool mirror[3] = bool[3](false, false, false);
    int side[3] = int[3](0, 0, 0);
    for (int a = 0; a < 3; ++a) {
        if (periodicAxis(a)) {
            index[a] = wrapIndex(index[a], cellCount()[a]);
        } else if (index[a] < 0) {
            index[a] = 0;
            mirror[a] = c != a && boundaryKind(a, false) == MFX_BOUNDARY_WALL_NO_SLIP;
            side[a] = 2 * a;
        } else if (index[a] > n[a] - 1) {
            index[a] = n[a] - 1;
            mirror[a] = c != a && boundaryKind(a, true) == MFX_BOUNDARY_WALL_NO_SLIP;
            side[a] = 2 * a + 1;
        }
    }
    for (int a = 0; a < 3; ++a) {
        if (mirror[a]) {
            ref.scale = -ref.scale;
            ref.offset = 2.0 * params.wallVelocity[side[a]][c] - ref.offset;
        }
    }
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
