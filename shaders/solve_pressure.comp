// solvePressure: one Jacobi sweep of sum over counted neighbours of (p_n - p) = h² div,
// p <- (sum of counted neighbour pressures - h² div) / count; walls are not counted, open faces
// count with p = 0, periodic ones wrap (docs/fluid.md). Twin: fluid/reference/solve_pressure.cpp.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, r32f) uniform readonly image3D divergence;
layout(binding = 2, r32f) uniform readonly image3D pressureIn;
layout(binding = 3, r32f) uniform writeonly image3D pressureOut;

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID);
    ivec3 n = cellCount();
    if (any(greaterThanEqual(q, n))) return;
    float sum = 0.0;
    int count = 0;
    for (int s = 0; s < 6; ++s) {
        int axis = s / 2;
        bool high = (s % 2) == 1;
        ivec3 neighbour = q;
        neighbour[axis] += high ? 1 : -1;
        uint kind = boundaryKind(axis, high);
        if (neighbour[axis] >= 0 && neighbour[axis] < n[axis]) {
            sum += imageLoad(pressureIn, neighbour).r;
            ++count;
        } else if (kind == MFX_BOUNDARY_PERIODIC) {
            neighbour[axis] = wrapIndex(neighbour[axis], n[axis]);
            sum += imageLoad(pressureIn, neighbour).r;
            ++count;
        } else if (kind == MFX_BOUNDARY_OPEN) {
            ++count;
        }
    }
    float h = cellSize();
    float p = count > 0 ? (sum - h * h * imageLoad(divergence, q).r) / float(count) : 0.0;
    imageStore(pressureOut, q, vec4(p));
}
