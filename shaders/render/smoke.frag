// The smoke pass's march as a fragment shader (smoke_march.glsl) over the faces of the pigment's
// box turned away from the eye (smoke.vert), into the cleared fluid buffer: each texel whose ray
// meets the box is shaded once. The CPU device's march (render/smoke_pass.h); smoke_march.comp is
// the GPU's.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "smoke_march.glsl"

layout(location = 0) out vec4 outColor;     // premultiplied
layout(location = 1) out float outDistance; // marchedDistance() of the scene distance used

void main() {
    float marched;
#ifdef MFX_SMOKE_CARTOON // (built as smoke_frag_cartoon: the surface's margin, light and distance)
    outColor = marchCartoon(ivec2(gl_FragCoord.xy),
                            rayDirection(gl_FragCoord.xy * float(kDivisor)), marched);
#else
    outColor = march(ivec2(gl_FragCoord.xy), rayDirection(gl_FragCoord.xy * float(kDivisor)),
                     marched);
#endif
    outDistance = marched;
}
