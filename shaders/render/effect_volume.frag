// Motion volumes: Blinn-Phong with the key light (as the scene pass), premultiplied alpha.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "effect_common.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec4 vertexColour;

layout(location = 0) out vec4 outColor;

void main() {
    vec3 n = normalize(worldNormal);
    if (!gl_FrontFacing) n = -n;
    vec3 l = normalize(frame.lightDirection.xyz);
    vec3 v = normalize(frame.cameraPosition.xyz - worldPosition);
    float diffuse = max(dot(n, l), 0.0);
    float specular = diffuse > 0.0 ? pow(max(dot(n, normalize(l + v)), 0.0), frame.ground.w) : 0.0;
    vec3 ambient = frame.lightColor.w * mix(frame.ground.rgb, frame.sky.rgb, 0.5 + 0.5 * n.y);
    vec3 color = vertexColour.rgb * (ambient + diffuse * frame.lightColor.rgb) +
                 frame.sky.w * specular * frame.lightColor.rgb;
    float a = vertexColour.a;
    outColor = vec4(color * a, a);
}
