// What the smoke pass's march (smoke_march.comp) and composite (smoke_composite.frag), and the
// box's vertices (smoke.vert), share: the draw's push constants, the pigment's box, the mapping
// between pixels, clip space and the world, and the ray's stretch in a box. The including shader
// declares `sceneDepth`, the full-resolution scene depth.
#ifndef MFX_SMOKE_COMMON_GLSL
#define MFX_SMOKE_COMMON_GLSL

#include "smoke_box.glsl"

layout(push_constant) uniform Draw {
    SmokeDraw draw;
};

// The fluid buffer has 1 / kDivisor of the picture's width and height (SmokeResolution).
layout(constant_id = 0) const int kDivisor = 2;

// The pigment's box in world units, from the vertex stage (shaders/render/smoke.vert) or, in the
// compute march, set by its main (smoke_box.glsl).
#ifdef MFX_SMOKE_COMPUTE
vec3 boxLow, boxHigh;
#else
layout(location = 0) flat in vec3 boxLow;
layout(location = 1) flat in vec3 boxHigh;
#endif

// A point of the full-resolution picture (pixels, top row first) in clip space. The target's
// viewport is flipped (+y up), so clip y runs against the rows.
vec2 toClip(vec2 pixel) {
    vec2 uv = pixel / vec2(textureSize(sceneDepth, 0));
    return vec2(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);
}

vec3 toWorld(vec2 xy, float depth) {
    vec4 p = draw.inverseViewProjection * vec4(xy, depth, 1.0);
    return p.xyz / p.w;
}

// The unit direction from the eye through a point of the picture.
vec3 rayDirection(vec2 pixel) {
    return normalize(toWorld(toClip(pixel), 1.0) - draw.eye.xyz);
}

// How far from the eye lies the scene surface seen by a pixel.
float sceneDistanceAt(ivec2 pixel) {
    float depth = texelFetch(sceneDepth, pixel, 0).r;
    return length(toWorld(toClip(vec2(pixel) + 0.5), depth) - draw.eye.xyz);
}

// Where the ray eye + t dir (inv = 1 / dir) enters and leaves the box [lo, hi], entering at t >= 0;
// it misses the box when the second is not above the first.
vec2 crossBox(vec3 inv, vec3 lo, vec3 hi) {
    vec3 t0 = (lo - draw.eye.xyz) * inv, t1 = (hi - draw.eye.xyz) * inv;
    float enter = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), 0.0));
    float leave = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), max(t0.z, t1.z));
    return vec2(enter, leave);
}

// The depth-fade distance b (docs/architecture.md "Formulas").
float fadeDistance() {
    return max(draw.eye.w, 1e-4);
}

// What of a scene distance matters to the march of any ray through the pigment's box: nothing
// beyond the box's farthest corner (all of the pigment is in front), nor nearer than b before the
// box's nearest point (all of it is hidden). Texels whose clamped distances agree marched the same
// stretch. The bounds are the same for every ray, so neighbouring rays that graze the box still
// compare as their neighbours do.
float marchedDistance(float sceneDistance) {
    vec3 eye = draw.eye.xyz;
    float nearest = length(clamp(eye, boxLow, boxHigh) - eye);
    float farthest = length(max(abs(boxLow - eye), abs(boxHigh - eye)));
    return clamp(sceneDistance, nearest - fadeDistance(), farthest);
}

#endif
