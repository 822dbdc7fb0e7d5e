// The scene pass, vertex stage: skinned vertices (written by skin_vertices.comp) or stage
// geometry in the same layout (position and normal as vec4), moved by the draw's model matrix.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/scene_draw.h"

layout(location = 0) in vec4 position;
layout(location = 1) in vec4 normal;

layout(std140, binding = 0) uniform Frame {
    SceneFrame frame;
};
layout(push_constant) uniform Object {
    SceneObject object;
};

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;

void main() {
    vec4 world = object.model * vec4(position.xyz, 1.0);
    worldPosition = world.xyz;
    worldNormal = transpose(inverse(mat3(object.model))) * normal.xyz;
    gl_Position = frame.viewProjection * world;
}
