// The lit test scene: Blinn-Phong with one directional light and an ambient term, in linear
// colour (the sRGB target encodes on write).
//   colour = base * (ambient + (1 - ambient) * max(n·l, 0)) * light + strength * max(n·h, 0)^e *
//   light
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/test_scene.h"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;

layout(std140, binding = 0) uniform Frame {
    TestSceneFrame frame;
};
layout(push_constant) uniform Object {
    TestSceneObject object;
};

layout(location = 0) out vec4 outColor;

void main() {
    vec3 n = normalize(worldNormal);
    vec3 l = normalize(frame.lightDirection.xyz);
    vec3 v = normalize(frame.cameraPosition.xyz - worldPosition);
    vec3 h = normalize(l + v);
    float ambient = frame.lightColor.w;
    float diffuse = max(dot(n, l), 0.0);
    float specular = diffuse > 0.0 ? pow(max(dot(n, h), 0.0), frame.specular.y) : 0.0;
    vec3 color =
        object.baseColor.rgb * (ambient + (1.0 - ambient) * diffuse) * frame.lightColor.rgb +
        frame.specular.x * specular * frame.lightColor.rgb;
    outColor = vec4(color, 1.0);
}
