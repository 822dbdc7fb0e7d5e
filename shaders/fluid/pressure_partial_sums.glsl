// Partial sums of the GPU pressure solvers' dot products and means: each workgroup of a level-0
// dispatch writes the sum of its invocations' values into partials[slot * pc.partials + group];
// finish_reduction adds a slot's partials up. Sums are taken in a fixed order (subgroups, then
// the subgroups' sums in order), so a result does not change from run to run. No twin: the
// reference sums in double, in array order.
#ifndef MFX_PRESSURE_PARTIAL_SUMS_GLSL
#define MFX_PRESSURE_PARTIAL_SUMS_GLSL

#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require

shared vec4 subgroupSums[256]; // maxComputeWorkGroupInvocations (1024) / a subgroup of 4 or more

// Every invocation of the workgroup must call this (it has a barrier), with 0 where it has no
// cell.
void writePartialSums(vec4 value) {
    vec4 sum = subgroupAdd(value);
    if (subgroupElect()) subgroupSums[gl_SubgroupID] = sum;
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        vec4 total = vec4(0.0);
        for (uint i = 0u; i < gl_NumSubgroups; ++i)
            total += subgroupSums[i];
        uint group = gl_WorkGroupID.x +
                     gl_NumWorkGroups.x * (gl_WorkGroupID.y + gl_NumWorkGroups.y * gl_WorkGroupID.z);
        partials[pc.slot * pc.partials + group] = total;
    }
}

#endif
