// finishReduction: adds up the partial sums of slots `slot` and `slot` + 1 (written by the
// workgroups of a level-0 dispatch, shaders/fluid/pressure_partial_sums.glsl) and takes the scalar step
// `step` (MFX_REDUCE_*) of the solve: a mean, or the scalars of a preconditioned conjugate
// gradient iteration and its stopping test. Twin: the scalar arithmetic of solvePressureMgpcg in
// fluid/reference/mgpcg.cpp (Saad, "Iterative Methods for Sparse Linear Systems", 2003, alg. 9.1)
// and consistentRightHandSide in fluid/reference/pressure_equation.cpp.
//
// When CG stops (tolerance met, (d, A d) not positive, b = 0), the first `limit` indirect dispatch
// entries are set to no workgroups: the iterations recorded after it then do nothing.
//
// One workgroup. pc: step, slot, partials, scale = tolerance, limit, flags: MFX_PRESSURE_SINGULAR,
// MFX_PRESSURE_FIRST, MFX_PRESSURE_COUNT_CELLS.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "pressure_solve_common.glsl"

shared vec4 subgroupSums[2][256];

void stop() {
    scalars.done = 1u;
    for (uint i = 0u; i < pc.limit; ++i)
        arguments[i] = uvec4(0u);
}

void main() {
    uint groupSize = gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z;
    uint lane = gl_LocalInvocationIndex;
    vec4 a = vec4(0.0), b = vec4(0.0);
    for (uint i = lane; i < pc.partials; i += groupSize) {
        a += partials[pc.slot * pc.partials + i];
        b += partials[(pc.slot + 1u) * pc.partials + i];
    }
    a = subgroupAdd(a);
    b = subgroupAdd(b);
    if (subgroupElect()) {
        subgroupSums[0][gl_SubgroupID] = a;
        subgroupSums[1][gl_SubgroupID] = b;
    }
    barrier();
    if (lane != 0u) return;
    vec4 first = vec4(0.0), second = vec4(0.0);
    for (uint i = 0u; i < gl_NumSubgroups; ++i) {
        first += subgroupSums[0][i];
        second += subgroupSums[1][i];
    }
    // The cells a mean is over (all, or the fluid ones with solids), counted by
    // load_pressure_system and kept by the mean of b.
    if (pc.step == MFX_REDUCE_MEAN && hasFlag(MFX_PRESSURE_COUNT_CELLS))
        scalars.fluidCells = first.y;
    float cells = scalars.fluidCells;
    bool singular = hasFlag(MFX_PRESSURE_SINGULAR);
    float tolerance = pc.scale;

    if (pc.step == MFX_REDUCE_MEAN) {
        scalars.mean = first.x / cells;
    } else if (pc.step == MFX_REDUCE_CG_START) {
        // first.x = (b, b), second.x = (r, r), both made mean-free when singular.
        float norm = sqrt(first.x);
        scalars.rightHandSideNorm = norm;
        scalars.iterations = 0u;
        scalars.done = 0u;
        scalars.zeroSolution = norm == 0.0 ? 1u : 0u;
        float relative = norm > 0.0 ? sqrt(second.x) / norm : 0.0;
        scalars.relativeResidual = relative;
        if (norm == 0.0 || relative <= tolerance) stop();
    } else if (pc.step == MFX_REDUCE_CG_ALPHA) {
        float dq = first.x;
        scalars.dq = dq;
        if (!(dq > 0.0)) {
            stop(); // d = 0: r = 0 already
        } else {
            scalars.alpha = scalars.rz / dq;
        }
    } else if (pc.step == MFX_REDUCE_CG_CHECK) {
        scalars.iterations += 1u;
        float relative = sqrt(first.x) / scalars.rightHandSideNorm;
        scalars.relativeResidual = relative;
        if (relative <= tolerance) stop();
    } else if (pc.step == MFX_REDUCE_CG_BETA) {
        // first = ((r, z), sum z, sum r): (r, z - mean) = (r, z) - mean sum r.
        float mean = singular ? first.y / cells : 0.0;
        float rz = first.x - mean * first.z;
        scalars.mean = mean;
        scalars.beta = hasFlag(MFX_PRESSURE_FIRST) ? 0.0 : rz / scalars.rz;
        scalars.rz = rz;
    }
}
