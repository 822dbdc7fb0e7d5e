// splatImpulses on the sparse grid: emitters pull the stored values of one target (velocity x,
// y, z or pigment; kTarget) of the listed bricks towards their own (docs/fluid.md). The dense
// stage's formula (splat_impulses.comp), the emitters tested against each brick's box first.
// Solid faces and cells are left alone (docs/fluid.md, "Solids"). In place: each invocation writes
// only its own values. Twin: fluid/reference/splat_impulses.cpp
// with the reference's active cells.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_solids.glsl"

layout(std430, binding = 3) readonly buffer Emitters {
    FluidEmitter emitters[];
};
layout(std430, binding = 4) buffer VelocityX {
    float velocityX[];
};
layout(std430, binding = 5) buffer VelocityY {
    float velocityY[];
};
layout(std430, binding = 6) buffer VelocityZ {
    float velocityZ[];
};
layout(std430, binding = 7) buffer Pigment {
    vec4 pigment[];
};

// As splat_impulses.comp: 0 outside the radius and for an emitter with a non-finite or
// non-positive radius or a bad strength (buffers filled on the GPU are not checked on the CPU).
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

// Emitters whose sphere reaches this brick (a bit each, the first kMaskedEmitters; any beyond are
// tested one by one), in the emitters' order: the pull towards each in turn depends on it.
const uint kMaskedEmitters = 4096u;
shared uint reaching[kMaskedEmitters / 32u];

bool reachesBox(FluidEmitter e, vec3 lo, vec3 hi) {
    float r = e.positionRadius.w;
    vec3 d = max(max(lo - e.positionRadius.xyz, e.positionRadius.xyz - hi), vec3(0.0));
    return r > 0.0 && dot(d, d) < r * r; // false for NaN
}

vec4 pulled(vec4 value, vec3 x, int c, uint masked, uint count) {
    bool pigmentTarget = kTarget == MFX_TARGET_PIGMENT;
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
    return value;
}

void splatFace(BrickCell at, int c, ivec3 l, uint masked, uint count) {
    ivec3 q = at.brick * kBrick + l;
    if (wallNormalFace(c, q) || sparseSolidFace(c, q)) return; // solid faces keep the solid's
    int e = faceElementIn(at.slot, c, l);
    float v = c == 0 ? velocityX[e] : (c == 1 ? velocityY[e] : velocityZ[e]);
    v = pulled(vec4(v), facePosition(c, q), c, masked, count).x;
    if (c == 0)
        velocityX[e] = v;
    else if (c == 1)
        velocityY[e] = v;
    else
        velocityZ[e] = v;
}

void main() {
    BrickCell at = listedCell();
    uint count = min(params.size.w, uint(emitters.length()));
    uint masked = min(count, kMaskedEmitters);
    // The brick's box, one cell wider on every side (its cell centres and all its faces lie in it).
    vec3 lo = (vec3(at.brick * kBrick) - 1.0) * cellSize();
    vec3 hi = (vec3(at.brick * kBrick + kBrick) + 1.0) * cellSize();
    uint invocations = gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z;
    for (uint w = gl_LocalInvocationIndex; w < (masked + 31u) / 32u; w += invocations)
        reaching[w] = 0u;
    barrier();
    for (uint i = gl_LocalInvocationIndex; i < masked; i += invocations)
        if (reachesBox(emitters[i], lo, hi)) atomicOr(reaching[i / 32u], 1u << (i % 32u));
    barrier();

    if (kTarget == MFX_TARGET_PIGMENT) {
        int e = cellElementIn(at.slot, at.local);
        if (solidElement(e)) return; // no pigment inside a solid
        pigment[e] = pulled(pigment[e], cellCentre(at.brick * kBrick + at.local), 0, masked, count);
        return;
    }
    int c = int(kTarget);
    splatFace(at, c, at.local, masked, count);
    if (at.local[c] == kBrick - 1) {
        ivec3 top = at.local;
        top[c] = kBrick;
        splatFace(at, c, top, masked, count);
    }
}
