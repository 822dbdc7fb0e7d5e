// Motion volumes (blur): the side walls each triangle sweeps, from the trajectory ring, lit with
// their stored normals; alpha from the attenuation and the age.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"

layout(location = 0) in vec4 position; // xyz, w: tau
layout(location = 1) in vec4 normal;   // xyz, w: sample time
layout(location = 2) in vec4 colour;

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec4 vertexColour;

void main() {
    worldPosition = position.xyz;
    worldNormal = normal.xyz;
    vertexColour = vec4(colour.rgb * draw.tint.rgb, colour.a * draw.tint.a * ageFade(normal.w));
    gl_Position = frame.viewProjection * vec4(position.xyz, 1.0);
}
