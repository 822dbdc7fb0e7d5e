// The scene pass, fragment stage: Blinn-Phong with the key light, and a hemisphere ambient that
// blends the sky colour (normals up) into the ground colour (normals down), in linear colour:
//   colour = base * (ambient(n) + max(n·l, 0) * light) + strength * max(n·h, 0)^e * light
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/scene_draw.h"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;

layout(std140, binding = 0) uniform Frame {
    SceneFrame frame;
};
layout(push_constant) uniform Object {
    SceneObject object;
};

layout(location = 0) out vec4 outColor;

void main() {
    vec3 n = normalize(worldNormal);
    if (!gl_FrontFacing) n = -n; // thin geometry (a blade) lit from its visible side
    vec3 l = normalize(frame.lightDirection.xyz);
    vec3 v = normalize(frame.cameraPosition.xyz - worldPosition);
    vec3 h = normalize(l + v);
    float diffuse = max(dot(n, l), 0.0);
    float specular = diffuse > 0.0 ? pow(max(dot(n, h), 0.0), frame.ground.w) : 0.0;
    vec3 ambient = frame.lightColor.w * mix(frame.ground.rgb, frame.sky.rgb, 0.5 + 0.5 * n.y);
    vec3 color = object.baseColor.rgb * (ambient + diffuse * frame.lightColor.rgb) +
                 frame.sky.w * specular * frame.lightColor.rgb;
    outColor = vec4(color, 1.0);
}
