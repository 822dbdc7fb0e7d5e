// Self-test of the geometry stage: each point becomes a quad (two triangles in a strip).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/selftest.h"

layout(points) in;
layout(triangle_strip, max_vertices = 4) out;

layout(push_constant) uniform Constants {
    PointsToQuadsConstants constants;
};

void main() {
    vec4 centre = gl_in[0].gl_Position;
    vec2 h = constants.halfSize;
    gl_Position = centre + vec4(-h.x, -h.y, 0.0, 0.0);
    EmitVertex();
    gl_Position = centre + vec4(h.x, -h.y, 0.0, 0.0);
    EmitVertex();
    gl_Position = centre + vec4(-h.x, h.y, 0.0, 0.0);
    EmitVertex();
    gl_Position = centre + vec4(h.x, h.y, 0.0, 0.0);
    EmitVertex();
    EndPrimitive();
}
