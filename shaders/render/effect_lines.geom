// Speed-lines: each line piece becomes a ribbon `width` * width_over_life(u) wide, or without
// that curve tapering along the segment and with age: width * (1 - 0.7 tau) * alpha. Each end is
// offset across the direction of the line at that sample: the bisector of the two pieces that
// meet there (ribbon_joins.comp), so that neighbouring pieces, within a segment and across the weld
// between two frames' segments, share their edge points and the ribbon's edges run as one curve. Without joins (draw.ribbonShape.x = 0), the piece's own
// direction at both ends.
//   * flat, facing the camera: a quad across the piece, perpendicular to it and to the view;
//   * flat, facing the blade: a quad in the plane of the surface the line comes from, through the
//     motion (side = n x along, n the source's normal; its face is n made perpendicular to the
//     motion), so a sword's lines lie in its slash plane; where n runs along the motion, as the
//     camera's;
//   * tube (Xu et al., Sec. 3.2.2: lines extended to tubes for more complex shading): the half of
//     a round tube around the piece that faces the camera, in kTubeSteps facets, each vertex
//     carrying the tube's normal for the key light (effect_lines.frag). The back half is left out:
//     an opaque tube hides it, and a translucent or additive one would count the light twice.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"
#include "ribbon_style.glsl"

const int kTubeSteps = 6;

layout(lines) in;
layout(triangle_strip, max_vertices = 2 * (kTubeSteps + 1)) out;

layout(location = 0) in vec4 vertexColour[];
layout(location = 1) in float vertexTau[];
layout(location = 2) in float vertexLife[];
layout(location = 3) in vec3 vertexNormal[];
layout(location = 4) in vec4 vertexJoin[];
layout(location = 5) in float vertexU[];

layout(location = 0) out vec4 ribbonColour;
layout(location = 1) out float across; // -1 .. 1 over the ribbon's width (cos of the tube angle)
layout(location = 2) out vec3 tubeNormal; // world; the tube's, or 0 on a flat ribbon
layout(location = 3) out vec2 texCoord;   // u along the line, v 0..1 across it
layout(location = 4) out float life;

float halfWidthAt(int k) {
    return draw.ribbonFlags.y > 0.5
               ? 0.5 * draw.timing.z * widthOverLife(vertexLife[k])
               : 0.5 * draw.timing.z * (1.0 - 0.7 * vertexTau[k]) * max(vertexColour[k].a, 0.15);
}

void emit(int k, vec3 offset, float acrossValue, vec3 normal) {
    ribbonColour = vertexColour[k];
    across = acrossValue;
    texCoord = vec2(vertexU[k], 0.5 + 0.5 * acrossValue);
    life = vertexLife[k];
    tubeNormal = normal;
    gl_Position = frame.viewProjection * vec4(gl_in[k].gl_Position.xyz + offset, 1.0);
    EmitVertex();
}

// The side (unit, across the line) at end k of the piece, whose direction there is `along`.
vec3 sideAt(int k, vec3 along, bool tube) {
    vec3 p = gl_in[k].gl_Position.xyz;
    vec3 side = cross(along, normalize(frame.cameraPosition.xyz - p));
    if (draw.ribbonFlags.w > 0.5 && !tube) {
        vec3 n = vertexNormal[k];
        vec3 blade = cross(n, along);
        // Not where the normal runs along the motion (within about half a degree).
        if (dot(blade, blade) > 1e-4 * dot(n, n) * dot(along, along)) side = blade;
    }
    return dot(side, side) < 1e-14 ? vec3(0.0) : normalize(side);
}

void main() {
    vec3 a = gl_in[0].gl_Position.xyz;
    vec3 b = gl_in[1].gl_Position.xyz;
    vec3 piece = b - a;
    if (dot(piece, piece) < 1e-14) return; // no motion: no line
    bool tube = draw.ribbonLight.z > 0.5;
    vec3 along[2] = vec3[2](piece, piece);
    for (int k = 0; k < 2; ++k)
        if (dot(vertexJoin[k].xyz, vertexJoin[k].xyz) > 0.5) along[k] = vertexJoin[k].xyz;
    vec3 side[2] = vec3[2](sideAt(0, along[0], tube), sideAt(1, along[1], tube));
    if (dot(side[0], side[0]) < 0.5 || dot(side[1], side[1]) < 0.5) return; // seen end-on
    float halfWidth[2] = float[2](halfWidthAt(0), halfWidthAt(1));
    if (!tube) {
        for (int k = 0; k < 2; ++k)
            for (int s = -1; s <= 1; s += 2)
                emit(k, float(s) * halfWidth[k] * side[k], float(s), vec3(0.0));
    } else {
        // Towards the camera: side x along . view > 0.
        vec3 toward[2] = vec3[2](normalize(cross(side[0], along[0])),
                                 normalize(cross(side[1], along[1])));
        for (int j = 0; j <= kTubeSteps; ++j) {
            float angle = 3.14159265 * float(j) / float(kTubeSteps);
            for (int k = 0; k < 2; ++k) {
                vec3 d = cos(angle) * side[k] + sin(angle) * toward[k];
                emit(k, halfWidth[k] * d, cos(angle), d);
            }
        }
    }
    EndPrimitive();
}
