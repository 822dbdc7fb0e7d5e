// solvePressure: one Jacobi sweep of sum over counted neighbours of (p_n - p) = h² div,
// p <- (sum of counted neighbour pressures - h² div) / count; walls are not counted, open faces
// count with p = 0, periodic ones wrap (docs/fluid.md). Twin: fluid/reference/solve_pressure.cpp.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, r32f) uniform readonly image3D divergence;
layout(binding = 2, r32f) uniform readonly image3D pressureIn;
layout(binding = 3, r32f) uniform writeonly image3D pressureOut;

// Adds neighbour `neighbour` (one step along `axis` towards `high`) of a cell to the sweep's sum
// and count. Branch-free (a CPU driver executes both sides of every branch): the load always
// reads a valid texel, and selects decide whether it counts.
void addNeighbour(ivec3 neighbour, int axis, bool high, inout float sum, inout int count) {
    int n = cellCount()[axis];
    uint kind = boundaryKind(axis, high);
    bool inside = neighbour[axis] >= 0 && neighbour[axis] < n;
    bool periodic = kind == MFX_BOUNDARY_PERIODIC;
    neighbour[axis] = periodic ? wrapIndex(neighbour[axis], n) : clamp(neighbour[axis], 0, n - 1);
    float value = imageLoad(pressureIn, neighbour).r;
    sum += (inside || periodic) ? value : 0.0; // adding 0.0 leaves the sum exactly as skipping
    count += (inside || periodic || kind == MFX_BOUNDARY_OPEN) ? 1 : 0; // open: ghost p = 0
}

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(q, cellCount()))) return;
    float h = cellSize();
    float divergenceTerm = h * h * imageLoad(divergence, q).r;
    float sum = 0.0;
    int count = 0;
    // The reference's order: -x, +x, -y, +y, -z, +z.
    addNeighbour(q - ivec3(1, 0, 0), 0, false, sum, count);
    addNeighbour(q + ivec3(1, 0, 0), 0, true, sum, count);
    addNeighbour(q - ivec3(0, 1, 0), 1, false, sum, count);
    addNeighbour(q + ivec3(0, 1, 0), 1, true, sum, count);
    addNeighbour(q - ivec3(0, 0, 1), 2, false, sum, count);
    addNeighbour(q + ivec3(0, 0, 1), 2, true, sum, count);
    float p = count > 0 ? (sum - divergenceTerm) / float(count) : 0.0;
    imageStore(pressureOut, q, vec4(p));
}
