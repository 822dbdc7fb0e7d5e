// Speed-lines: each line piece becomes a ribbon facing the camera (a quad across the piece,
// perpendicular to it and to the view direction), `width` * width_over_life(u) wide, or without
// that curve tapering along the segment and with age: width * (1 - 0.7 tau) * alpha.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"
#include "ribbon_style.glsl"

layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

layout(location = 0) in vec4 vertexColour[];
layout(location = 1) in float vertexTau[];
layout(location = 2) in float vertexLife[];

layout(location = 0) out vec4 ribbonColour;
layout(location = 1) out float across; // -1 .. 1 over the ribbon's width

void main() {
    vec3 a = gl_in[0].gl_Position.xyz;
    vec3 b = gl_in[1].gl_Position.xyz;
    vec3 along = b - a;
    if (dot(along, along) < 1e-14) return; // no motion: no line
    vec3 view = normalize(frame.cameraPosition.xyz - 0.5 * (a + b));
    vec3 side = cross(along, view);
    if (dot(side, side) < 1e-14) return; // seen end-on
    side = normalize(side);
    for (int k = 0; k < 2; ++k) {
        vec3 p = k == 0 ? a : b;
        float halfWidth = draw.ribbonFlags.y > 0.5
                              ? 0.5 * draw.timing.z * widthOverLife(vertexLife[k])
                              : 0.5 * draw.timing.z * (1.0 - 0.7 * vertexTau[k]) *
                                    max(vertexColour[k].a, 0.15);
        for (int s = -1; s <= 1; s += 2) {
            ribbonColour = vertexColour[k];
            across = float(s);
            gl_Position = frame.viewProjection * vec4(p + float(s) * halfWidth * side, 1.0);
            EmitVertex();
        }
    }
    EndPrimitive();
}
