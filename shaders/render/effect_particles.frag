// Motion particles: a round soft dot, alpha (1 - d^2) at distance d from its centre (d = 1 at the
// rim), premultiplied, its colour times the look's HDR intensity; additive particles add their
// light (alpha 0) instead of covering what is behind; it fades out in front of the scene's
// surfaces (depth_fade.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"
#include "depth_fade.glsl"

layout(location = 0) in vec4 spriteColour;
layout(location = 1) in vec2 corner;

layout(location = 0) out vec4 outColor;

void main() {
    float d2 = dot(corner, corner);
    if (d2 > 1.0) discard;
    float a = clamp(spriteColour.a * (1.0 - d2) * depthFade(draw.ribbonLight.w), 0.0, 1.0);
    outColor = vec4(spriteColour.rgb * draw.ribbonLight.x * a, draw.ribbonFlags.z > 0.5 ? 0.0 : a);
}
