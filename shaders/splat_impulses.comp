// splatImpulses: emitters pull velocity and pigment towards their own values (docs/fluid.md).
// Twin: fluid/reference/splat_impulses.cpp. One dispatch per target (velocity x, y, z, pigment).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(std430, binding = 1) readonly buffer Emitters {
    FluidEmitter emitters[];
};
layout(binding = 2, r32f) uniform image3D velocityX;
layout(binding = 3, r32f) uniform image3D velocityY;
layout(binding = 4, r32f) uniform image3D velocityZ;
layout(binding = 5, rgba32f) uniform image3D pigment;

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

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID) +
              ivec3(dispatchInfo.originX, dispatchInfo.originY, dispatchInfo.originZ);
    uint target = kTarget;
    // Bounded by the buffer's own length as well: never reads past the bound range. It also keeps
    // the loop bound from being a pure uniform, which a CPU driver (lavapipe) would otherwise fold
    // into a freshly compiled shader variant on every dispatch.
    uint count = min(params.size.w, uint(emitters.length()));
    if (target == MFX_TARGET_PIGMENT) {
        if (any(greaterThanEqual(q, cellCount()))) return;
        vec3 x = cellCentre(q);
        vec4 value = imageLoad(pigment, q);
        for (uint i = 0; i < count; ++i) {
            FluidEmitter e = emitters[i];
            float a = emitterWeight(e, x);
            if (a > 0.0) value += a * (e.pigment - value);
        }
        imageStore(pigment, q, value);
        return;
    }
    int c = int(target);
    if (any(greaterThanEqual(q, faceCount(c))) || wallNormalFace(c, q)) return;
    vec3 x = facePosition(c, q);
    float value = c == 0 ? imageLoad(velocityX, q).r
                         : (c == 1 ? imageLoad(velocityY, q).r : imageLoad(velocityZ, q).r);
    for (uint i = 0; i < count; ++i) {
        FluidEmitter e = emitters[i];
        float a = emitterWeight(e, x);
        if (a > 0.0) value += a * (e.velocityStrength[c] - value);
    }
    if (c == 0)
        imageStore(velocityX, q, vec4(value));
    else if (c == 1)
        imageStore(velocityY, q, vec4(value));
    else
        imageStore(velocityZ, q, vec4(value));
}
