// The host's own shading: a flat colour lit by one light from above and the front, with a little
// ambient light (nothing of motionfx's look).
#version 450

layout(push_constant) uniform Draw {
    mat4 viewProjection;
    vec4 colour;
} draw;

layout(location = 0) in vec3 worldNormal;
layout(location = 0) out vec4 outColour;

void main() {
    vec3 n = normalize(worldNormal);
    float light = 0.25 + 0.75 * max(dot(n, normalize(vec3(0.3, 0.9, 0.5))), 0.0);
    outColour = vec4(draw.colour.rgb * light, 1.0);
}
