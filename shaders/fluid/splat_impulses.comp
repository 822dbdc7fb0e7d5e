// splatImpulses: emitters pull velocity and pigment towards their own values (docs/fluid.md).
// Twin: fluid/reference/splat_impulses.cpp. One dispatch per target (velocity x, y, z, pigment).
// It runs over the region emitterBounds wrote (an indirect dispatch; shaders/fluid/emitter_bounds.comp).
// Each workgroup first marks the emitters that reach its block of the grid, so a cell loops over
// those only (a scene's hundreds of segment emitters touch a few blocks each).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#include "fluid_solids.glsl"

layout(std430, binding = 1) readonly buffer Emitters {
    FluidEmitter emitters[];
};
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform image3D velocityX;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform image3D velocityY;
layout(binding = 4, MFX_VELOCITY_FORMAT) uniform image3D velocityZ;
layout(binding = 5, MFX_PIGMENT_FORMAT) uniform image3D pigment;
layout(std430, binding = 6) readonly buffer Regions {
    SplatRegion regions[4];
};

// Blend weight of emitter e at x over one sub-step; 0 outside its radius and for emitters whose
// fields are not finite or whose radius is not positive (buffers filled on the GPU are not
// checked on the CPU).
float emitterWeight(FluidEmitter e, vec3 x) {
    float r = e.positionRadius.w;
    float s = e.velocityStrength.w;
    if (!(r > 0.0) || !(s >= 0.0) || isinf(r) || isinf(s) || any(isnan(e.positionRadius.xyz)) ||
        any(isinf(e.positionRadius.xyz)))
        return 0.0;
    vec3 d = x - e.positionRadius.xyz;
    float r2 = r * r;
    float d2 = dot(d, d);
    if (d2 >= r2) return 0.0;
    float t = 1.0 - d2 / r2;
    return 1.0 - exp(-s * t * t * timeStep());
}

// Emitters whose sphere reaches this workgroup's block, as a bit per emitter (the first
// kMaskedEmitters; any beyond are tested one by one). Bits keep the emitters' order, and the pull
// towards each emitter in turn depends on that order, as in the reference.
const uint kMaskedEmitters = 4096u;
shared uint reaching[kMaskedEmitters / 32u];

// Whether emitter e's sphere reaches the box [lo, hi] (world units of the grid).
bool reachesBox(FluidEmitter e, vec3 lo, vec3 hi) {
    float r = e.positionRadius.w;
    vec3 d = max(max(lo - e.positionRadius.xyz, e.positionRadius.xyz - hi), vec3(0.0));
    return r > 0.0 && dot(d, d) < r * r; // false for NaN
}

void main() {
    uint target = kTarget;
    // Bounded by the buffer's own length as well: never reads past the bound range. It also keeps
    // the loop bound from being a pure uniform, which a CPU driver (lavapipe) would otherwise fold
    // into a freshly compiled shader variant on every dispatch.
    uint count = min(params.size.w, uint(emitters.length()));
    uint masked = min(count, kMaskedEmitters);

    // The block this workgroup covers, one cell wider on every side (cell centres and faces of
    // every component lie within it).
    uvec3 size = gl_WorkGroupSize;
    ivec3 origin =
        ivec3(regions[target].originX, regions[target].originY, regions[target].originZ);
    ivec3 first = ivec3(gl_WorkGroupID * size) + origin;
    vec3 lo = (vec3(first) - 1.0) * cellSize();
    vec3 hi = (vec3(first + ivec3(size)) + 1.0) * cellSize();
    uint invocations = size.x * size.y * size.z;
    for (uint w = gl_LocalInvocationIndex; w < (masked + 31u) / 32u; w += invocations)
        reaching[w] = 0u;
    barrier();
    for (uint i = gl_LocalInvocationIndex; i < masked; i += invocations)
        if (reachesBox(emitters[i], lo, hi)) atomicOr(reaching[i / 32u], 1u << (i % 32u));
    barrier();

    ivec3 q = ivec3(gl_GlobalInvocationID) + origin;
    int c = int(target);
    bool pigmentTarget = target == MFX_TARGET_PIGMENT;
    // Solid cells hold no pigment and solid faces keep the solid's velocity (docs/fluid.md,
    // "Solids").
    if (pigmentTarget) {
        if (any(greaterThanEqual(q, cellCount())) || solidCell(q)) return;
    } else if (any(greaterThanEqual(q, faceCount(c))) || wallNormalFace(c, q) || solidFace(c, q)) {
        return;
    }
    vec3 x = pigmentTarget ? cellCentre(q) : facePosition(c, q);
    vec4 value = pigmentTarget
                     ? imageLoad(pigment, q)
                     : vec4(c == 0 ? imageLoad(velocityX, q).r
                                   : (c == 1 ? imageLoad(velocityY, q).r : imageLoad(velocityZ, q).r));
    for (uint word = 0u; word < (masked + 31u) / 32u; ++word) {
        uint bits = reaching[word];
        while (bits != 0u) {
            uint i = word * 32u + uint(findLSB(bits));
            bits &= bits - 1u;
            FluidEmitter e = emitters[i];
            float a = emitterWeight(e, x);
            if (a > 0.0) {
                if (pigmentTarget)
                    value += a * (e.pigment - value);
                else
                    value.x += a * (e.velocityStrength[c] - value.x);
            }
        }
    }
    for (uint i = masked; i < count; ++i) {
        FluidEmitter e = emitters[i];
        float a = emitterWeight(e, x);
        if (a > 0.0) {
            if (pigmentTarget)
                value += a * (e.pigment - value);
            else
                value.x += a * (e.velocityStrength[c] - value.x);
        }
    }
    if (pigmentTarget)
        imageStore(pigment, q, MFX_STORED4(value));
    else if (c == 0)
        imageStore(velocityX, q, vec4(MFX_STORED(value.x)));
    else if (c == 1)
        imageStore(velocityY, q, vec4(MFX_STORED(value.x)));
    else
        imageStore(velocityZ, q, vec4(MFX_STORED(value.x)));
}
