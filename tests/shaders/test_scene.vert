// The lit test scene: world-space position and normal for Blinn-Phong shading.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/test_scene.h"

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;

layout(std140, binding = 0) uniform Frame {
    TestSceneFrame frame;
};
layout(push_constant) uniform Object {
    TestSceneObject object;
};

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;

void main() {
    vec4 world = object.model * vec4(position, 1.0);
    worldPosition = world.xyz;
    // Inverse transpose keeps normals perpendicular under non-uniform scale.
    worldNormal = transpose(inverse(mat3(object.model))) * normal;
    gl_Position = frame.viewProjection * world;
}
