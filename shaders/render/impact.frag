// The impact's quads shaded (impact.vert): a spark streak brightest along its middle and at its
// head, fading to its tail; the flash a soft round glow (a Gaussian, e^(-4 r^2)); the ring a band
// between its inner and outer radius with soft edges. Premultiplied; additive draws add their
// light (alpha 0); all fade out in front of the scene's surfaces (depth_fade.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "impact_common.glsl"
#include "depth_fade.glsl"

layout(location = 0) in vec4 vertexColour;
layout(location = 1) in vec2 corner;

layout(location = 0) out vec4 outColor;

void main() {
    float a;
    if (draw.centre.w == MFX_IMPACT_SPARKS) {
        float across = 1.0 - corner.x * corner.x;
        float along = 0.25 + 0.75 * (0.5 * corner.y + 0.5);
        a = vertexColour.a * across * along;
    } else if (draw.centre.w == MFX_IMPACT_FLASH) {
        float r2 = dot(corner, corner);
        if (r2 > 1.0) discard;
        a = vertexColour.a * exp(-4.0 * r2);
    } else {
        float r = length(corner);
        float inner = draw.ring.x, outer = draw.ring.y;
        float halfBand = max(0.5 * (outer - inner), 1e-4);
        float d = abs(r - 0.5 * (inner + outer)) / halfBand;
        if (d > 1.0) discard;
        a = vertexColour.a * (1.0 - d * d);
    }
    a = clamp(a * depthFade(draw.ring.w), 0.0, 1.0);
    outColor = vec4(vertexColour.rgb * a, draw.ring.z > 0.5 ? 0.0 : a);
}
