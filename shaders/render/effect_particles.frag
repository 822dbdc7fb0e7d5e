// Motion particles: a round soft dot, premultiplied.
#version 450

layout(location = 0) in vec4 spriteColour;
layout(location = 1) in vec2 corner;

layout(location = 0) out vec4 outColor;

void main() {
    float d2 = dot(corner, corner);
    if (d2 > 1.0) discard;
    float a = spriteColour.a * (1.0 - d2);
    outColor = vec4(spriteColour.rgb * a, a);
}
