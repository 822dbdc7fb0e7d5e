// The scene pass, fragment stage. Lit: Blinn-Phong with the key light, and a hemisphere ambient
// that blends the sky colour (normals up) into the ground colour (normals down), in linear colour:
//   colour = base * (ambient(n) + s * max(n·l, 0) * light) + s * strength * max(n·h, 0)^e * light
// where s is the fraction of the key light's shadow map that sees the light under a tent filter
// over 3x3 texels (percentage-closer filtering).
// Toon (cel shading as in Guilty Gear Xrd's published pipeline: a light ramp with a few flat
// tones, a rim light, inverted-hull outlines drawn by outline.vert): the lit fraction
// d = s * max(n·l, 0) is read from a ramp of N levels, level k = k / (N - 1) for d in
// [k / N, (k + 1) / N), with a one-pixel smooth step between levels (fwidth) against stair-steps;
//   colour = base * (ambient + ramp(d) * light) + rim * light * step(0.6, (1 - n·v) * ramp(d))
// with a flat ambient (the hemisphere's middle), so each level is one flat tone; the rim lights
// the lit side's silhouette.
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
layout(binding = 1) uniform sampler2DShadow shadowMap;

float lit(vec3 world, vec3 n, vec3 l) {
    if (frame.shadow.x == 0.0) return 1.0;
    vec4 clip = frame.lightViewProjection * vec4(world, 1.0);
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z > 1.0)
        return 1.0; // outside the map: lit
    // More bias where the light grazes the surface.
    float bias = frame.shadow.y * (1.0 + 4.0 * (1.0 - max(dot(n, l), 0.0)));
    // Four linearly filtered comparisons half a texel either side: each is a 2x2 percentage-closer
    // filter, together a tent over 3x3 texels (weights 1 2 1 by 1 2 1, / 16) in four fetches
    // instead of nine (a CPU driver runs every fetch, whichever side of a branch it is on).
    float sum = 0.0;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
            sum += texture(shadowMap,
                           vec3(uv + (vec2(x, y) - 0.5) * frame.shadow.z, ndc.z - bias));
    return 0.25 * sum;
}

layout(location = 0) out vec4 outColor;

// The ramp's level at lit fraction d: N flat levels, each edge smoothed over about a pixel.
float ramp(float d, float levels) {
    float x = d * levels;
    float k = min(floor(x), levels - 1.0);
    float blur = max(fwidth(x), 1e-4);
    // Within half a pixel of the next level's start, blend into it.
    float up = k < levels - 1.0 ? smoothstep(k + 1.0 - blur, k + 1.0, x) : 0.0;
    return (k + up) / (levels - 1.0);
}

vec3 toon(vec3 n, vec3 l, vec3 v, float shade) {
    float levels = object.style.y;
    float level = ramp(max(dot(n, l), 0.0) * shade, levels);
    vec3 ambient = frame.lightColor.w * mix(frame.ground.rgb, frame.sky.rgb, 0.5);
    float edge = (1.0 - max(dot(n, v), 0.0)) * level;
    float blur = max(fwidth(edge), 1e-4);
    float rim = object.style.z * smoothstep(0.6 - blur, 0.6, edge);
    return object.baseColor.rgb * (ambient + level * frame.lightColor.rgb) +
           rim * frame.lightColor.rgb;
}

void main() {
    vec3 n = normalize(worldNormal);
    if (!gl_FrontFacing) n = -n; // thin geometry (a blade) lit from its visible side
    vec3 l = normalize(frame.lightDirection.xyz);
    vec3 v = normalize(frame.cameraPosition.xyz - worldPosition);
    vec3 h = normalize(l + v);
    float shade = lit(worldPosition, n, l);
    if (object.style.x == MFX_STYLE_TOON) {
        outColor = vec4(toon(n, l, v, shade), 1.0);
        return;
    }
    float diffuse = max(dot(n, l), 0.0) * shade;
    float specular = diffuse > 0.0 ? shade * pow(max(dot(n, h), 0.0), frame.ground.w) : 0.0;
    vec3 ambient = frame.lightColor.w * mix(frame.ground.rgb, frame.sky.rgb, 0.5 + 0.5 * n.y);
    vec3 color = object.baseColor.rgb * (ambient + diffuse * frame.lightColor.rgb) +
                 frame.sky.w * specular * frame.lightColor.rgb;
    outColor = vec4(color, 1.0);
}
