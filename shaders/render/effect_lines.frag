// Speed-lines: a bright core fading to the ribbon's edges, over the picture (premultiplied), its
// colour times the ribbon's HDR intensity; additive ribbons add their light (alpha 0 in the
// premultiplied blend) instead of covering what is behind. A textured ribbon's colour is
// multiplied by its texture and eroded (ribbon_texture.glsl) first. A tube is lit as the character's lit
// style is, without specular: colour * (hemisphere ambient(n) + max(n.l, 0) * light); a flat
// ribbon is its own light. Each fades out in front of the scene's surfaces (depth_fade.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"
#include "ribbon_style.glsl"
#include "depth_fade.glsl"
#include "ribbon_texture.glsl"

layout(location = 0) in vec4 ribbonColour;
layout(location = 1) in float across;
layout(location = 2) in vec3 tubeNormal;
layout(location = 3) in vec2 texCoord;
layout(location = 4) in float life;

// The ribbon's texture (a white texel where it has none; read only with one).
layout(binding = 5) uniform sampler2D ribbonTexture;

layout(location = 0) out vec4 outColor;

void main() {
    // Interpolation may carry `across` a little past the edge: the picture is HDR, where a
    // negative weight is not clamped away.
    vec4 colour = textured(ribbonColour, texCoord, life, ribbonTexture);
    float edge = clamp(1.0 - across * across, 0.0, 1.0);
    float a = clamp(colour.a * edge * depthFade(draw.ribbonLight.w), 0.0, 1.0);
    vec3 core = mix(colour.rgb, vec3(1.0), draw.ribbonLight.y * edge * edge); // hot centre
    vec3 shade = vec3(1.0);
    if (draw.ribbonLight.z > 0.5) {
        vec3 n = normalize(tubeNormal);
        vec3 ambient = frame.lightColor.w * mix(frame.ground.rgb, frame.sky.rgb, 0.5 + 0.5 * n.y);
        shade = ambient + max(dot(n, normalize(frame.lightDirection.xyz)), 0.0) * frame.lightColor.rgb;
    }
    vec3 light = core * shade * draw.ribbonLight.x * a;
    outColor = vec4(light, draw.ribbonFlags.z > 0.5 ? 0.0 : a);
}
