// Speed-lines: trajectory vertices passed on to the geometry stage, which widens each piece of a
// motion line into a ribbon or a tube (effect_lines.geom), with the direction along the line the
// joins pass gave the vertex (ribbon_joins.comp). Each vertex's life u = age /
// lifetime; its colour is the ribbon's colour_over_life at u (times the segment's attenuation),
// or without one the trail's colour faded with age (Xu et al., Algorithm 1); its texture's u, by
// the texture's mode (ribbon_texture.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"
#include "ribbon_style.glsl"
#include "ribbon_texture.glsl"

layout(location = 0) in vec4 position;
layout(location = 1) in vec4 normal;
layout(location = 2) in vec4 colour;

layout(location = 0) out vec4 vertexColour;
layout(location = 1) out float vertexTau;
layout(location = 2) out float vertexLife;
layout(location = 3) out vec3 vertexNormal; // the source's normal (blade facing)
layout(location = 4) out vec4 vertexJoin;   // xyz: direction along the line, or 0: none
layout(location = 5) out float vertexU;     // the texture's u

// The direction along the line at each ring vertex, shared by the pieces that meet there
// (ribbon_joins.comp); read only with draw.ribbonShape.x = 1.
layout(std430, binding = 3) readonly buffer Joins {
    vec4 joins[];
};
// Each ring vertex's distance along its line from where the line began (ribbon_distance.comp);
// read only with the texture's distance mode.
layout(std430, binding = 4) readonly buffer Distances {
    float distances[];
};

void main() {
    float fade = ageFade(normal.w);
    vertexLife = 1.0 - fade;
    if (draw.ribbonFlags.x > 0.5) {
        // The stored alpha is the source's alpha times the attenuation at tau.
        vec4 c = colourOverLife(vertexLife);
        vertexColour = vec4(c.rgb * draw.tint.rgb, c.a * colour.a * draw.tint.a);
    } else {
        vertexColour = vec4(colour.rgb * draw.tint.rgb, colour.a * draw.tint.a * fade);
    }
    vertexTau = position.w;
    vertexNormal = normal.xyz;
    vertexJoin = draw.ribbonShape.x > 0.5 ? joins[gl_VertexIndex] : vec4(0.0);
    float distance = draw.ribbonTexture.x > 3.5 ? distances[gl_VertexIndex] : 0.0;
    vertexU = ribbonU(normal.w, position.w, distance);
    gl_Position = vec4(position.xyz, 1.0); // world space; projected in the geometry stage
}
