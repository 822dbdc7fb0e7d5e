// computeDivergence: div = (u[i+1]-u[i] + v[j+1]-v[j] + w[k+1]-w[k]) / h (docs/fluid.md).
// Twin: fluid/reference/compute_divergence.cpp. Writes a buffer that the solver copies into the
// divergence image, or with kDirectStore the image itself.
//
// In a step whose Jacobi pressure solve starts cold (SolverOptions::firstSweepInDivergence), the
// same pass also does the solve's first sweep: with every pressure 0 the sweep of
// solve_pressure.comp gives p = (0 - h² div) / count, the cell's own divergence over its counted
// neighbours, so it needs nothing another invocation computes. kFirstSweep says where it goes:
// 1, packed as solve_pressure.comp's sweeps between the first and the last keep it (the divergence
// packed beside it; each row's padding written 0); 2, into the pressure image (a grid too large
// for the packed buffers, or a solve of one sweep). The pressure solve then starts at its second
// sweep: one dispatch, its barrier and a read of the divergence fewer.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#include "fluid_solids.glsl"
#include "jacobi_neighbours.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityX;
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityY;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityZ;
layout(std430, binding = 4) writeonly buffer Divergence {
    float divergence[];
};
layout(binding = 5, r32f) uniform writeonly image3D divergenceImage; // kDirectStore
// kFirstSweep 1: the packed divergence and pressure, cell by cell.
layout(std430, binding = 6) writeonly buffer PackedDivergence {
    float packedDivergence[];
};
layout(std430, binding = 7) writeonly buffer PackedPressure {
    float packedPressure[];
};
// kFirstSweep 2.
layout(binding = 8, MFX_PRESSURE_FORMAT) uniform writeonly image3D pressureOut;

layout(constant_id = 11) const uint kFirstSweep = 0;

void main() {
    ivec3 q = stageInvocation();
    ivec3 n = cellCount();
    if (any(greaterThanEqual(q, n))) return;
    float sum = (imageLoad(velocityX, q + ivec3(1, 0, 0)).r - imageLoad(velocityX, q).r) +
                (imageLoad(velocityY, q + ivec3(0, 1, 0)).r - imageLoad(velocityY, q).r) +
                (imageLoad(velocityZ, q + ivec3(0, 0, 1)).r - imageLoad(velocityZ, q).r);
    // A solid cell has no pressure unknown, and so no divergence to remove (docs/fluid.md,
    // "Solids").
    bool near = solidsNearWorkgroup();
    bool solid = near && solidCell(q);
    float div = solid ? 0.0 : sum / cellSize();
    if (kDirectStore)
        imageStore(divergenceImage, q, vec4(div));
    else
        divergence[cellElement(q)] = div;
    if (kFirstSweep == 0u) return;

    // As solve_pressure.comp computes a cold first sweep, operation for operation.
    float h = cellSize();
    float h2 = h * h;
    int count = jacobiNeighbourCount(q) - bitCount(near ? solidNeighbours(q) : 0u);
    float p = count == 0 || solid ? 0.0 : (0.0 - h2 * div) / float(count);
    if (kFirstSweep == 1u) {
        int element = 4 * packedIndex(0, q.y, q.z);
        packedDivergence[element + q.x] = div;
        packedPressure[element + q.x] = p;
        if (q.x == n.x - 1) // the row's padding, read by no cell
            for (int x = n.x; x < 4 * ((n.x + 3) / 4); ++x) {
                packedDivergence[element + x] = 0.0;
                packedPressure[element + x] = 0.0;
            }
    } else {
        imageStore(pressureOut, q, vec4(MFX_STORED(p)));
    }
}
