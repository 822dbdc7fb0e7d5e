// Motion particles: trajectory vertices passed on to the geometry stage, which makes each a
// camera-facing sprite (effect_particles.geom).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"

layout(location = 0) in vec4 position;
layout(location = 1) in vec4 normal;
layout(location = 2) in vec4 colour;

layout(location = 0) out vec4 vertexColour;

void main() {
    vertexColour = vec4(colour.rgb * draw.tint.rgb, colour.a * draw.tint.a * ageFade(normal.w));
    gl_Position = vec4(position.xyz, 1.0);
}
