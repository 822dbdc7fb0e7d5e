// The impact's quads, six vertices each, made here without a vertex buffer:
//   sparks (one quad per spark, instanced by vertex index): a streak from the spark's tail to its
//     head (impact_sparks.comp), `axisV.w` wide times the look's size over life, turned to the
//     camera about its own axis; colour over life times the draw's colour;
//   flash: a camera-facing square of half size axisU.w at the centre;
//   ring: a square of half size axisU.w at the centre, facing the camera (axisU zero) or spanned
//     by axisU and axisV (the hit plane).
// `corner` is the vertex's place on the quad: x across (-1..1), y along (-1..1; sparks: 1 at the
// head, -1 at the tail).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "impact_common.glsl"
#include "ribbon_style.glsl"

layout(std430, binding = 3) readonly buffer Streaks {
    ImpactStreak streaks[];
};

layout(location = 0) out vec4 vertexColour;
layout(location = 1) out vec2 corner;

const vec2 kCorners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1),
                                vec2(-1, 1));

// Two unit axes across the view at p: right and up as the camera sees them.
void cameraAxes(vec3 p, out vec3 right, out vec3 up) {
    vec3 view = normalize(p - frame.cameraPosition.xyz);
    vec3 r = cross(view, vec3(0.0, 1.0, 0.0));
    right = dot(r, r) > 1e-8 ? normalize(r) : vec3(1.0, 0.0, 0.0);
    up = cross(right, view);
}

void main() {
    vec2 c = kCorners[gl_VertexIndex % 6];
    corner = c;
    vec3 p;
    if (draw.centre.w == MFX_IMPACT_SPARKS) {
        ImpactStreak s = streaks[gl_VertexIndex / 6];
        float u = s.head.w;
        bool alive = u >= 0.0 && u < 1.0;
        vec3 head = s.head.xyz, tail = s.tail.xyz;
        vec3 along = head - tail;
        vec3 view = head - frame.cameraPosition.xyz;
        vec3 side = cross(along, view);
        if (dot(side, side) < 1e-12) {
            vec3 up;
            cameraAxes(head, side, up);
        }
        side = normalize(side);
        float halfWidth = 0.5 * draw.axisV.w * widthOverLife(clamp(u, 0.0, 1.0));
        p = mix(tail, head, 0.5 * c.y + 0.5) + side * (c.x * halfWidth);
        vec4 look = colourOverLife(clamp(u, 0.0, 1.0));
        vertexColour = alive ? vec4(look.rgb * draw.colour.rgb, look.a * draw.colour.a) : vec4(0.0);
        if (!alive) p = head; // a degenerate quad: nothing drawn
    } else {
        vec3 u, v;
        vec3 centre = draw.centre.xyz;
        if (dot(draw.axisU.xyz, draw.axisU.xyz) > 0.0) {
            u = draw.axisU.xyz;
            v = draw.axisV.xyz;
        } else {
            cameraAxes(centre, u, v);
        }
        p = centre + (u * c.x + v * c.y) * draw.axisU.w;
        vertexColour = draw.colour;
    }
    gl_Position = frame.viewProjection * vec4(p, 1.0);
}
