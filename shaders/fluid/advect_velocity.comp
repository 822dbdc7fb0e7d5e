// advectVelocity: advection of each MAC face component through the velocity as it was on entry
// (docs/fluid.md; Stam 1999, eq. 7 for the semi-Lagrangian step; MacCormack after Selle et al.
// 2008 and BFECC after Kim et al. 2005, both limited), then the per-second drag,
// u *= exp(-drag * dt). Twins: fluid/reference/advect_velocity.cpp, semi_lagrangian.cpp,
// maccormack.cpp, bfecc.cpp. One dispatch per component and pass (kPass, MFX_ADVECT_*), writing a
// buffer that the solver copies into an image (the component's work image for the next pass, or
// its new velocity after the last one), or with kDirectStore (semi-Lagrangian only) the new
// velocity image itself.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#include "fluid_solids.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityX;
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityY;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityZ;
layout(std430, binding = 4) writeonly buffer Out {
    float outValues[];
};
// The component kTarget's intermediate field (unused by the semi-Lagrangian and predict passes).
layout(binding = 5, MFX_VELOCITY_FORMAT) uniform readonly image3D work;
layout(binding = 6, MFX_VELOCITY_FORMAT) uniform writeonly image3D outField; // kDirectStore

layout(constant_id = 11) const uint kPass = MFX_ADVECT_SEMI_LAGRANGIAN;

const int kWorkField = 1;

float loadFaceField(int field, int c, ivec3 index) {
    if (field == kWorkField) return imageLoad(work, index).r;
    return c == 0 ? imageLoad(velocityX, index).r
                  : (c == 1 ? imageLoad(velocityY, index).r : imageLoad(velocityZ, index).r);
}

#include "fluid_sampling.glsl"

void main() {
    int c = int(kTarget);
    ivec3 q = stageInvocation();
    if (any(greaterThanEqual(q, faceCount(c)))) return;
    // The boundaries (docs/fluid.md, "Boundaries"): wall-normal faces are 0, and a periodic axis's
    // last face is its first, computed as face 0 so that the two agree bit for bit.
    ivec3 at = q;
    if (periodicAxis(c) && q[c] == cellCount()[c]) at[c] = 0;
    bool wallNormal = wallNormalFace(c, at);
    float value = 0.0;
    if (kPass == MFX_ADVECT_BFECC_COMPENSATE) {
        // A wall-normal face samples as 0, as in every semi-Lagrangian pass.
        float source = loadFaceField(kVelocityField, c, at);
        float returned =
            wallNormal ? 0.0 : sampleFace(kWorkField, c, backTraceFromFace(c, at, -timeStep()));
        value = source + 0.5 * (source - returned);
    } else if (!wallNormal) {
        vec3 departure = backTraceFromFace(c, at, timeStep());
        if (kPass == MFX_ADVECT_SEMI_LAGRANGIAN || kPass == MFX_ADVECT_PREDICT) {
            value = sampleFace(kVelocityField, c, departure);
        } else {
            if (kPass == MFX_ADVECT_MACCORMACK_CORRECT) {
                float source = loadFaceField(kVelocityField, c, at);
                float returned = sampleFace(kWorkField, c, backTraceFromFace(c, at, -timeStep()));
                value = imageLoad(work, at).r + 0.5 * (source - returned);
            } else { // MFX_ADVECT_BFECC_FINAL
                value = sampleFace(kWorkField, c, departure);
            }
            vec2 range = faceRange(kVelocityField, c, departure);
            value = clamp(value, range.x, range.y);
        }
        if (kPass != MFX_ADVECT_PREDICT) value *= exp(-params.cell.w * timeStep());
    }
    bool lastPass = kPass != MFX_ADVECT_PREDICT && kPass != MFX_ADVECT_BFECC_COMPENSATE;
    value = lastPass ? flushTiny(value) : value;
    // Solid faces move with the solid, not with the air: the last pass keeps the solid's velocity
    // they hold (docs/fluid.md, "Solids"); the passes before it advect them as any face.
    // (A periodic axis's last face is face 0, outside this workgroup's block.)
    bool near = any(notEqual(at, q)) || solidsNearWorkgroup();
    if (lastPass && near && solidFace(c, at)) value = loadFaceField(kVelocityField, c, at);
    if (kDirectStore)
        imageStore(outField, q, vec4(MFX_STORED(value)));
    else
        outValues[faceElement(c, q)] = value;
}
