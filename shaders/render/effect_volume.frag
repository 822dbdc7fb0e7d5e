// Lit effect volumes: Phong illumination as Xu et al. give it for motion volumes (Sec. 4.4.1; the
// Blinn-Phong of the scene pass), times the look's HDR intensity, plus a Fresnel rim light so the
// volume reads as energy: Schlick's F = F0 + (1 - F0) (1 - |n.v|)^5 with F0 = 0.04, times the
// rim's strength and colour, added as light where the volume covers (premultiplied). Additive
// volumes add their light (alpha 0) instead of covering what is behind.
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
    float fresnel = 0.04 + 0.96 * pow(1.0 - abs(dot(n, v)), 5.0);
    vec3 rim = draw.rimLight.x * fresnel * draw.rimLight.yzw;
    float a = clamp(vertexColour.a, 0.0, 1.0);
    outColor = vec4((color * draw.ribbonLight.x + rim) * a, draw.ribbonFlags.z > 0.5 ? 0.0 : a);
}
