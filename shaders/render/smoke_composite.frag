// The smoke pass's composite: the fluid buffer (smoke.frag, 1 / kDivisor of the picture's width
// and height) laid over the picture with premultiplied alpha, by a depth-aware upsample: of the
// four fluid texels around a pixel, only those whose marched scene distance is close to this
// pixel's count, with their bilinear weights (as in A. Pesce, "Low-resolution effects with
// depth-aware upsampling", 2016); where none is close, the closest one alone (the nearest-depth
// upsampling of J. Jansen and L. Bavoil, "Fast Rendering of Opacity-Mapped Particles using
// DirectX 11 Tessellation and Mixed Resolutions", NVIDIA whitepaper). Smoke thus keeps the
// character's and the floor's silhouettes at full resolution, without halos, and stays smooth
// elsewhere. Drawn over the same box as the march (shaders/render/smoke.vert).
//
// "Close" allows what a smooth surface changes over the distance from the pixel to the texel's
// sample (up to kDivisor + 1/2 pixels along each axis, at the pixel's own slope, taken on the
// side away from any edge), plus b / 4, which moves the depth fade by no more than a quarter.
// Distances are compared after marchedDistance(), so a surface far behind the pigment matches any
// other such surface; texels outside the pigment's box (not marched, no smoke) match every pixel,
// so the smoke fades out towards them as it does inside.
#version 450
#extension GL_GOOGLE_include_directive : require

layout(binding = 0) uniform sampler2D fluidColor;
layout(binding = 1) uniform sampler2D fluidDistance;
layout(binding = 3) uniform sampler2D sceneDepth;

#include "smoke_common.glsl"

layout(location = 0) out vec4 outColor; // premultiplied

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(sceneDepth, 0);
    // The scene surface hides all of the pigment on this ray.
    float sceneDistance = sceneDistanceAt(pixel);
    float enter = crossBox(1.0 / rayDirection(gl_FragCoord.xy), boxLow, boxHigh).x;
    if (sceneDistance + fadeDistance() <= enter) discard;
    float own = marchedDistance(sceneDistance);
    float slope = 0.0;
    for (int axis = 0; axis < 2; ++axis) {
        ivec2 offset = ivec2(axis == 0 ? 1 : 0, axis == 1 ? 1 : 0);
        float before = marchedDistance(sceneDistanceAt(clamp(pixel - offset, ivec2(0), size - 1)));
        float after = marchedDistance(sceneDistanceAt(clamp(pixel + offset, ivec2(0), size - 1)));
        slope += min(abs(after - own), abs(own - before));
    }
    float tolerance = 0.25 * fadeDistance() + (float(kDivisor) + 0.5) * slope;
    // The four texels around the pixel, and its bilinear weights between them.
    vec2 at = gl_FragCoord.xy / float(kDivisor) - 0.5;
    ivec2 base = ivec2(floor(at));
    vec2 f = at - floor(at);
    ivec2 lowSize = textureSize(fluidColor, 0);
    vec4 sum = vec4(0.0);
    float weightSum = 0.0;
    vec4 closest = vec4(0.0);
    float closestGap = 3.0e38;
    for (int k = 0; k < 4; ++k) {
        ivec2 corner = ivec2(k & 1, k >> 1);
        ivec2 texel = clamp(base + corner, ivec2(0), lowSize - 1);
        vec2 w2 = mix(1.0 - f, f, vec2(corner));
        float weight = w2.x * w2.y;
        vec4 colour = texelFetch(fluidColor, texel, 0);
        float marched = texelFetch(fluidDistance, texel, 0).r;
        // No ray marched there: no smoke, whatever lies behind.
        float gap = marched <= 0.5 * MFX_SMOKE_NO_DISTANCE ? 0.0 : abs(marched - own);
        if (gap <= tolerance) {
            sum += weight * colour;
            weightSum += weight;
        }
        if (gap < closestGap) {
            closestGap = gap;
            closest = colour;
        }
    }
    vec4 result = weightSum > 1e-4 ? sum / weightSum : closest;
    if (result.a <= 1e-4) discard;
    outColor = result;
}
