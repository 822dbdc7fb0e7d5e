// The cartoon look's composite (smoke_cartoon.glsl marched the fluid buffer): the surface drawn at
// the picture's resolution, in flat bands with an ink outline, over the box's faces
// (shaders/render/smoke.vert), premultiplied.
//
// Each pixel reconstructs the surface from the four fluid texels around it: the margin m
// bilinearly (continuous across the silhouette, so its zero is the silhouette at sub-texel
// precision), and the light and distance from those of the texels whose ray met the surface, by
// their bilinear weights. Then:
//   the distance to the silhouette in pixels, d = m / |grad m| (the gradient of the bilinear m),
//   gives the edge's coverage, clamp(d + 1/2, 0, 1): a hard edge one pixel wide, not a stair of
//   2x2 blocks;
//   the light, quantised into `bands` (k = floor(light x bands)), picks band k's flat colour: the
//   bands' edges are the light's level lines, at full resolution;
//   ink where d < outline width (the silhouette's line, inside it), and where the surface steps in
//   depth: a neighbour `width` pixels away (of four) whose surface lies more than four cells
//   farther, or is hidden by the scene (a fighter in front): McGuire & Fein's outlines at
//   silhouettes and depth discontinuities;
//   the depth fade against this pixel's own scene distance D, alpha x= saturate(1 - (t - D) / b),
//   so the fighters cut the smoke at their own edges and it meets the floor softly.
#version 450
#extension GL_GOOGLE_include_directive : require

layout(binding = 0) uniform sampler2D fluidColor;    // (m, light, met, 0)
layout(binding = 1) uniform sampler2D fluidDistance; // the surface's distance where met
layout(binding = 3) uniform sampler2D sceneDepth;

#include "smoke_common.glsl"

layout(std140, binding = 4) uniform Style {
    SmokeStyle style;
};

layout(location = 0) out vec4 outColor; // premultiplied

struct Surface {
    float margin;    // m
    vec2 gradient;   // of m, per pixel
    float light;     // 0..1, before quantising
    float distance;  // from the eye
    bool met;        // whether any texel around met the surface
};

// The surface as reconstructed at a point of the picture (pixels).
Surface surfaceAt(vec2 pixel) {
    vec2 at = pixel / float(kDivisor) - 0.5;
    ivec2 base = ivec2(floor(at));
    vec2 f = at - floor(at);
    ivec2 lowSize = textureSize(fluidColor, 0);
    vec4 c[4];
    float t[4];
    for (int k = 0; k < 4; ++k) {
        ivec2 texel = clamp(base + ivec2(k & 1, k >> 1), ivec2(0), lowSize - 1);
        c[k] = texelFetch(fluidColor, texel, 0);
        t[k] = texelFetch(fluidDistance, texel, 0).r;
    }
    Surface s;
    s.margin = mix(mix(c[0].r, c[1].r, f.x), mix(c[2].r, c[3].r, f.x), f.y);
    s.gradient = vec2(mix(c[1].r - c[0].r, c[3].r - c[2].r, f.y),
                      mix(c[2].r - c[0].r, c[3].r - c[1].r, f.x)) /
                 float(kDivisor);
    float weightSum = 0.0, light = 0.0, distance = 0.0;
    for (int k = 0; k < 4; ++k) {
        vec2 w2 = mix(1.0 - f, f, vec2(k & 1, k >> 1));
        float w = w2.x * w2.y * c[k].b + 1e-6 * c[k].b;
        weightSum += w;
        light += w * c[k].g;
        distance += w * t[k];
    }
    s.met = weightSum > 0.0;
    s.light = s.met ? light / weightSum : 0.0;
    s.distance = s.met ? distance / weightSum : 0.0;
    return s;
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(sceneDepth, 0);
    Surface own = surfaceAt(gl_FragCoord.xy);
    float edge = own.margin / max(length(own.gradient), 1e-6); // pixels inside the silhouette
    float coverage = clamp(edge + 0.5, 0.0, 1.0);
    if (coverage <= 0.0 || !own.met) discard;
    float sceneDistance = sceneDistanceAt(pixel);
    float visible = clamp(1.0 - (own.distance - sceneDistance) / fadeDistance(), 0.0, 1.0);
    if (visible <= 0.0) discard;

    int bands = int(style.params.y);
    int band = clamp(int(floor(own.light * float(bands))), 0, bands - 1);
    vec3 colour = style.ramp[band].rgb;

    float width = style.outline.w;
    bool ink = edge < width;
    // Depth steps: a neighbour's surface far behind this one, or hidden by the scene.
    float depthStep = 4.0 * draw.gridOrigin.w;
    for (int k = 0; k < 4 && width > 0.0 && !ink; ++k) {
        vec2 offset = width * vec2(k == 0 ? 1 : k == 1 ? -1 : 0, k == 2 ? 1 : k == 3 ? -1 : 0);
        Surface next = surfaceAt(gl_FragCoord.xy + offset);
        if (next.margin <= 0.0 || !next.met) continue;
        ivec2 nextPixel = clamp(ivec2(gl_FragCoord.xy + offset), ivec2(0), size - 1);
        bool hidden = sceneDistanceAt(nextPixel) < next.distance - 0.5 * fadeDistance();
        ink = next.distance > own.distance + depthStep || hidden;
    }
    if (ink) colour = style.outline.rgb;
    float alpha = coverage * visible;
    outColor = vec4(colour * alpha, alpha);
}
