// Speed-lines: a bright core fading to the ribbon's edges, over the picture (premultiplied), its
// colour times the ribbon's HDR intensity; additive ribbons add their light (alpha 0 in the
// premultiplied blend) instead of covering what is behind. A tube is lit as the character's lit
// style is, without specular: colour * (hemisphere ambient(n) + max(n.l, 0) * light); a flat
// ribbon is its own light. Each fades out in front of the scene's surfaces (depth_fade.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"
#include "ribbon_style.glsl"
#include "depth_fade.glsl"

layout(location = 0) in vec4 ribbonColour;
layout(location = 1) in float across;
layout(location = 2) in vec3 tubeNormal;

layout(location = 0) out vec4 outColor;

void main() {
    // Interpolation may carry `across` a little past the edge: the picture is HDR, where a
    // negative weight is not clamped away.
    float edge = clamp(1.0 - across * across, 0.0, 1.0);
    float a = clamp(ribbonColour.a * edge * depthFade(draw.ribbonLight.w), 0.0, 1.0);
    vec3 core = mix(ribbonColour.rgb, vec3(1.0), draw.ribbonLight.y * edge * edge); // hot centre
    vec3 shade = vec3(1.0);
    if (draw.ribbonLight.z > 0.5) {
        vec3 n = normalize(tubeNormal);
        vec3 ambient = frame.lightColor.w * mix(frame.ground.rgb, frame.sky.rgb, 0.5 + 0.5 * n.y);
        shade = ambient + max(dot(n, normalize(frame.lightDirection.xyz)), 0.0) * frame.lightColor.rgb;
    }
    vec3 light = core * shade * draw.ribbonLight.x * a;
    outColor = vec4(light, draw.ribbonFlags.z > 0.5 ? 0.0 : a);
}
