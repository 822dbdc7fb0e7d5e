// Speed-lines: trajectory vertices passed on to the geometry stage, which widens each piece of a
// motion line into a camera-facing ribbon (effect_lines.geom).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"

layout(location = 0) in vec4 position;
layout(location = 1) in vec4 normal;
layout(location = 2) in vec4 colour;

layout(location = 0) out vec4 vertexColour;
layout(location = 1) out float vertexTau;

void main() {
    float fade = ageFade(normal.w);
    vertexColour = vec4(colour.rgb * draw.tint.rgb, colour.a * draw.tint.a * fade);
    vertexTau = position.w;
    gl_Position = vec4(position.xyz, 1.0); // world space; projected in the geometry stage
}
