// Speed-lines: a bright core fading to the ribbon's edges, over the picture (premultiplied), its
// colour times the ribbon's HDR intensity; additive ribbons add their light (alpha 0 in the
// premultiplied blend) instead of covering what is behind.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"
#include "ribbon_style.glsl"

layout(location = 0) in vec4 ribbonColour;
layout(location = 1) in float across;

layout(location = 0) out vec4 outColor;

void main() {
    // Interpolation may carry `across` a little past the edge: the picture is HDR, where a
    // negative weight is not clamped away.
    float edge = clamp(1.0 - across * across, 0.0, 1.0);
    float a = clamp(ribbonColour.a * edge, 0.0, 1.0);
    vec3 core = mix(ribbonColour.rgb, vec3(1.0), draw.ribbonLight.y * edge * edge); // hot centre
    vec3 light = core * draw.ribbonLight.x * a;
    outColor = vec4(light, draw.ribbonFlags.z > 0.5 ? 0.0 : a);
}
