// The smoke pass: a ray from the camera through the pixel marches the pigment volume (front to
// back, trilinear samples), with light absorption towards the key light so the smoke has shape,
// and stops at the scene's depth; the result is composited over the picture with premultiplied
// alpha, faded by how far behind the smoke lies the scene surface it meets (DESIGN.md "Formulas":
// alpha *= saturate(1 - (D_fluid - D_scene) / b)), so smoke meets the floor and the character
// softly. Pigment is RGBA with rgb = colour x alpha; density = alpha x scale.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/smoke_draw.h"

layout(location = 0) in vec2 ndc;

layout(push_constant) uniform Draw {
    SmokeDraw draw;
};
layout(binding = 0) uniform sampler3D pigment;
layout(binding = 1) uniform sampler2D sceneDepth;

layout(location = 0) out vec4 outColor;

vec3 toWorld(vec2 xy, float depth) {
    vec4 p = draw.inverseViewProjection * vec4(xy, depth, 1.0);
    return p.xyz / p.w;
}

vec4 sampleGrid(vec3 world) {
    vec3 uvw = (world - draw.gridOrigin.xyz) / (draw.gridOrigin.w * draw.gridSize.xyz);
    return texture(pigment, uvw);
}

void main() {
    // The target's viewport is flipped (+y up): texture rows run the other way.
    vec2 uv = vec2(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5);
    vec3 eye = draw.eye.xyz;
    vec3 far = toWorld(ndc, 1.0);
    vec3 dir = normalize(far - eye);
    float sceneDistance = length(toWorld(ndc, texture(sceneDepth, uv).r) - eye);
    // The ray's stretch inside the grid's box.
    vec3 lo = draw.gridOrigin.xyz;
    vec3 hi = lo + draw.gridOrigin.w * draw.gridSize.xyz;
    vec3 inv = 1.0 / dir;
    vec3 t0 = (lo - eye) * inv, t1 = (hi - eye) * inv;
    float tEnter = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
    float tExit = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), max(t0.z, t1.z));
    float fadeDistance = max(draw.eye.w, 1e-4);
    tExit = min(tExit, sceneDistance + fadeDistance);
    if (tExit <= tEnter) discard;
    float step = draw.gridOrigin.w / max(draw.gridSize.w, 0.25);
    int steps = min(int((tExit - tEnter) / step) + 1, 512);
    vec3 light = normalize(draw.light.xyz);
    float scale = draw.light.w;
    vec3 colour = vec3(0.0);
    float transmittance = 1.0;
    for (int i = 0; i < steps && transmittance > 0.01; ++i) {
        float t = tEnter + (float(i) + 0.5) * step;
        vec3 p = eye + t * dir;
        vec4 s = sampleGrid(p);
        float density = max(s.a, 0.0) * scale;
        if (density <= 1e-5) continue;
        // Behind the scene surface by d: faded linearly to nothing at d = b.
        float fade = clamp(1.0 - (t - sceneDistance) / fadeDistance, 0.0, 1.0);
        float a = (1.0 - exp(-density * step)) * fade;
        // Light reaching this sample: absorption along a few steps towards the light.
        float shadow = 0.0;
        for (int k = 1; k <= 4; ++k)
            shadow += max(sampleGrid(p + light * (float(k) * 2.0 * draw.gridOrigin.w)).a, 0.0);
        float lit = exp(-shadow * scale * 2.0 * draw.gridOrigin.w);
        vec3 albedo = s.rgb / max(s.a, 1e-4);
        colour += transmittance * a * albedo * (0.35 + 0.65 * lit);
        transmittance *= 1.0 - a;
    }
    float alpha = 1.0 - transmittance;
    if (alpha <= 1e-4) discard;
    outColor = vec4(colour, alpha); // premultiplied
}
