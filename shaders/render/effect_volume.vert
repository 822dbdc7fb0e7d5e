// Lit effect volumes: motion volumes (blur: the side walls each triangle sweeps, from the
// trajectory ring) and the mesh effects' built triangles (swept volumes, afterimage smears and
// arcs, silhouette shells), lit with their stored normals. Life u is the age over the lifetime,
// or for the mesh effects the place along the sweep (position.w: 0 at the live mesh); the colour
// is the look's colour_over_life at u (times the stored attenuation) or the vertex colour faded
// with age.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"
#include "ribbon_style.glsl"

layout(location = 0) in vec4 position; // xyz, w: tau, or the place along the sweep
layout(location = 1) in vec4 normal;   // xyz, w: sample time
layout(location = 2) in vec4 colour;

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec4 vertexColour;

void main() {
    worldPosition = position.xyz;
    worldNormal = normal.xyz;
    float fade = ageFade(normal.w);
    if (draw.ribbonFlags.x > 0.5) {
        float life = draw.ribbonFlags.w > 0.5 ? clamp(position.w, 0.0, 1.0) : 1.0 - fade;
        vec4 c = colourOverLife(life);
        vertexColour = vec4(c.rgb * draw.tint.rgb, c.a * colour.a * draw.tint.a);
    } else {
        vertexColour = vec4(colour.rgb * draw.tint.rgb, colour.a * draw.tint.a * fade);
    }
    gl_Position = frame.viewProjection * vec4(position.xyz, 1.0);
}
