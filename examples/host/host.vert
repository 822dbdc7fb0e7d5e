// The host's own vertex shader: world-space positions and normals (the host skins nothing: the
// character comes from mfxGetCharacterMesh already posed), one camera matrix.
#version 450

layout(push_constant) uniform Draw {
    mat4 viewProjection;
    vec4 colour;
} draw;

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 0) out vec3 worldNormal;

void main() {
    worldNormal = normal;
    gl_Position = draw.viewProjection * vec4(position, 1.0);
}
