// The key light's shadow map: the scene pass's geometry (skinned vertices, stage) seen from the
// light, depth only. Push constant: light view-projection times the draw's model matrix.
#version 450

layout(location = 0) in vec4 position;

layout(push_constant) uniform Draw {
    mat4 lightModelViewProjection;
};

void main() {
    gl_Position = lightModelViewProjection * vec4(position.xyz, 1.0);
}
