// advectPigment: advection of the RGBA pigment through the velocity (semi-Lagrangian; MacCormack
// or BFECC, both limited, in passes as advect_velocity.comp), then the per-second fade
// (docs/fluid.md). Twins: fluid/reference/advect_pigment.cpp, semi_lagrangian.cpp, maccormack.cpp,
// bfecc.cpp. Writes a buffer that the solver copies into an image (the work image for the next
// pass, or the new pigment after the last one), or with kDirectStore (semi-Lagrangian only) the
// new pigment image itself.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#include "fluid_solids.glsl"
#include "solid_common.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityX;
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityY;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityZ;
layout(binding = 4, MFX_PIGMENT_FORMAT) uniform readonly image3D pigmentIn;
layout(std430, binding = 5) writeonly buffer PigmentOut {
    vec4 pigmentOut[];
};
// The pass's intermediate pigment (unused by the semi-Lagrangian and predict passes).
layout(binding = 6, MFX_PIGMENT_FORMAT) uniform readonly image3D work;
layout(binding = 7, MFX_PIGMENT_FORMAT) uniform writeonly image3D pigmentOutImage; // kDirectStore

layout(constant_id = 11) const uint kPass = MFX_ADVECT_SEMI_LAGRANGIAN;

float loadFaceField(int field, int c, ivec3 index) {
    return c == 0 ? imageLoad(velocityX, index).r
                  : (c == 1 ? imageLoad(velocityY, index).r : imageLoad(velocityZ, index).r);
}

#include "fluid_sampling.glsl"

const int kSourcePigment = 0;
const int kWorkPigment = 1;

vec4 fetchPigment(int field, ivec3 index) {
    ivec3 cell = resolveCell(index);
    return field == kWorkPigment ? imageLoad(work, cell) : imageLoad(pigmentIn, cell);
}

vec4 samplePigment(int field, vec3 x) {
    vec3 g = gridCoordinate(x, vec3(0.5));
    vec3 base = floor(g);
    vec3 f = g - base;
    ivec3 i0 = ivec3(base);
    vec4 corners[8]; // x fastest: corner k is i0 + (k & 1, (k >> 1) & 1, k >> 2)
    for (int corner = 0; corner < 8; ++corner)
        corners[corner] =
            fetchPigment(field, i0 + ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1));
    vec4 c00 = lerpValue(corners[0], corners[1], f.x);
    vec4 c10 = lerpValue(corners[2], corners[3], f.x);
    vec4 c01 = lerpValue(corners[4], corners[5], f.x);
    vec4 c11 = lerpValue(corners[6], corners[7], f.x);
    vec4 plain = lerpValue(lerpValue(c00, c10, f.y), lerpValue(c01, c11, f.y), f.z);
    uint solid = stageStencilCorners(i0); // corner k at bit k
    return solid != 0u ? sampleOutsideSolids(f, corners, solid) : plain;
}

// Per channel, the smallest and largest of the eight source values samplePigment interpolates.
void sourceRange(vec3 x, out vec4 low, out vec4 high) {
    ivec3 i0 = ivec3(floor(gridCoordinate(x, vec3(0.5))));
    low = fetchPigment(kSourcePigment, i0);
    high = low;
    for (int corner = 1; corner < 8; ++corner) {
        vec4 v = fetchPigment(kSourcePigment,
                              i0 + ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1));
        low = min(low, v);
        high = max(high, v);
    }
}

void main() {
    ivec3 q = stageInvocation();
    if (any(greaterThanEqual(q, cellCount()))) return;
    vec4 value;
    if (kPass == MFX_ADVECT_BFECC_COMPENSATE) {
        vec4 source = imageLoad(pigmentIn, q);
        value = source + 0.5 * (source - samplePigment(kWorkPigment, backTraceFromCell(q, -timeStep())));
    } else {
        vec3 departure = backTraceFromCell(q, timeStep());
        if (kPass == MFX_ADVECT_SEMI_LAGRANGIAN || kPass == MFX_ADVECT_PREDICT) {
            value = samplePigment(kSourcePigment, departure);
        } else {
            if (kPass == MFX_ADVECT_MACCORMACK_CORRECT) {
                vec4 returned = samplePigment(kWorkPigment, backTraceFromCell(q, -timeStep()));
                value = imageLoad(work, q) + 0.5 * (imageLoad(pigmentIn, q) - returned);
            } else { // MFX_ADVECT_BFECC_FINAL
                value = samplePigment(kWorkPigment, departure);
            }
            vec4 low, high;
            sourceRange(departure, low, high);
            value = clamp(value, low, high);
        }
        if (kPass != MFX_ADVECT_PREDICT) value = flushTiny(value * exp(-params.rates.x * timeStep()));
        // None inside a solid (docs/fluid.md, "Solids"): the last pass writes 0 there.
        if (kPass != MFX_ADVECT_PREDICT && solidsNearWorkgroup() && solidCell(q)) value = vec4(0.0);
    }
    if (kDirectStore)
        imageStore(pigmentOutImage, q, MFX_STORED4(value));
    else
        pigmentOut[cellElement(q)] = value;
}
