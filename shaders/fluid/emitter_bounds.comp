// emitterBounds: the region splatImpulses has to cover, from the emitters themselves, so emitters
// made on the GPU (fluid/segment_emitters.h) are splatted over their bounding box rather than the
// whole grid. It changes where the splat runs, never what it computes: every sample point within
// an emitter's radius lies in the region, with one index of margin, as the splat's weight is zero
// outside that radius (docs/fluid.md, "splatImpulses"). No reference twin: the CPU reference
// splats every cell.
//
// One workgroup: each invocation takes every 64th emitter, the boxes are merged in shared memory,
// and four invocations write the four targets' SplatRegion (an indirect dispatch and an origin).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/fluid.h"

layout(local_size_x = 64) in;

layout(std140, binding = 0) uniform Parameters {
    FluidParameters params;
};
layout(std430, binding = 1) readonly buffer Emitters {
    FluidEmitter emitters[];
};
layout(std430, binding = 2) writeonly buffer Regions {
    SplatRegion regions[4];
};

// The splat's workgroup shape (SolverOptions::workgroup), as in shaders/fluid/fluid_common.glsl.
layout(constant_id = 8) const uint kGroupX = 8;
layout(constant_id = 9) const uint kGroupY = 8;
layout(constant_id = 10) const uint kGroupZ = 1;

shared vec3 lows[64];
shared vec3 highs[64];

void main() {
    uint l = gl_LocalInvocationIndex;
    uint count = min(params.size.w, uint(emitters.length()));
    vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
    for (uint i = l; i < count; i += 64u) {
        vec3 p = emitters[i].positionRadius.xyz;
        float r = emitters[i].positionRadius.w;
        float s = emitters[i].velocityStrength.w;
        // The emitters splatImpulses gives a weight (its emitterWeight's test).
        if (!(r > 0.0) || !(s >= 0.0) || isinf(r) || isinf(s) || any(isnan(p)) || any(isinf(p)))
            continue;
        lo = min(lo, p - r);
        hi = max(hi, p + r);
    }
    lows[l] = lo;
    highs[l] = hi;
    barrier();
    for (uint stride = 32u; stride > 0u; stride >>= 1u) {
        if (l < stride) {
            lows[l] = min(lows[l], lows[l + stride]);
            highs[l] = max(highs[l], highs[l + stride]);
        }
        barrier();
    }
    if (l >= 4u) return;
    // Target l: velocity x, y, z faces (index + 0.5 off the face's own axis) or cell centres.
    ivec3 extent = ivec3(params.size.xyz);
    vec3 shift = vec3(0.5);
    if (l < 3u) {
        extent[l] += 1;
        shift[l] = 0.0;
    }
    lo = lows[0];
    hi = highs[0];
    uvec3 first = uvec3(0), groups = uvec3(0);
    if (all(lessThanEqual(lo, hi))) {
        // Sample positions (index + shift) * h inside [lo, hi], with a margin of one index.
        vec3 top = vec3(extent);
        vec3 a = clamp(floor(lo * params.cell.y - shift), vec3(0.0), top);
        vec3 b = clamp(ceil(hi * params.cell.y - shift) + 1.0, vec3(0.0), top);
        if (all(lessThan(a, b))) {
            first = uvec3(a);
            uvec3 size = uvec3(b) - first;
            uvec3 group = uvec3(kGroupX, kGroupY, kGroupZ);
            groups = (size + group - 1u) / group;
        }
    }
    regions[l].groupsX = groups.x;
    regions[l].groupsY = groups.y;
    regions[l].groupsZ = groups.z;
    regions[l].pad0 = 0u;
    regions[l].originX = first.x;
    regions[l].originY = first.y;
    regions[l].originZ = first.z;
    regions[l].pad1 = 0u;
}
