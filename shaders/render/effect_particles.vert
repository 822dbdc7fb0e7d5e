// Motion particles: trajectory vertices passed on to the geometry stage, which makes each a
// camera-facing sprite (effect_particles.geom). Each particle's life u = age / lifetime; its
// colour is the look's colour_over_life at u (times the segment's attenuation), or without one
// the trail's colour faded with age (Xu et al., Algorithm 1).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"
#include "ribbon_style.glsl"

layout(location = 0) in vec4 position;
layout(location = 1) in vec4 normal;
layout(location = 2) in vec4 colour;

layout(location = 0) out vec4 vertexColour;
layout(location = 1) out float vertexLife;

void main() {
    float fade = ageFade(normal.w);
    vertexLife = 1.0 - fade;
    if (draw.ribbonFlags.x > 0.5) {
        vec4 c = colourOverLife(vertexLife);
        vertexColour = vec4(c.rgb * draw.tint.rgb, c.a * colour.a * draw.tint.a);
    } else {
        vertexColour = vec4(colour.rgb * draw.tint.rgb, colour.a * draw.tint.a * fade);
    }
    gl_Position = vec4(position.xyz, 1.0);
}
