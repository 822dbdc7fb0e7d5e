// What the bloom's steps share (shaders/render/bloom_*.comp): push constants and the two filters
// of the progressive down- and up-sampling of J. Jimenez, "Next Generation Post Processing in Call
// of Duty: Advanced Warfare" (SIGGRAPH 2014 course): a 13-tap down-sample and a 3x3 tent
// up-sample, both read through a bilinear sampler (clamped at the edges). Both filters' weights
// sum to 1, and every 2x2 block the 13 taps average holds one texel of each parity, so a level
// keeps the mean of the level above it: the bloom moves light, it does not add or remove it.
#ifndef MFX_BLOOM_COMMON_GLSL
#define MFX_BLOOM_COMMON_GLSL

#include "shared/post.h"

layout(local_size_x = MFX_BLOOM_GROUP_X, local_size_y = MFX_BLOOM_GROUP_Y) in;

layout(push_constant) uniform Step {
    BloomStep step;
};

// fp16 holds at most 65504: stacked additive light can overflow to infinity, and a NaN spreads to
// every texel the bloom touches. Each tap is kept finite, non-negative and within fp16.
vec3 finiteLight(vec3 c) {
    bvec3 bad = isnan(c);
    return clamp(vec3(bad.x ? 0.0 : c.x, bad.y ? 0.0 : c.y, bad.z ? 0.0 : c.z), 0.0, 65504.0);
}

// The 13 taps around `uv` of a texture of texel size `t`: four overlapping 2x2 boxes around the
// centre (weight 0.5 together) and four boxes at the corners of a 4x4 block, shared by the centre
// box (0.125 each, the shared taps weighted so that the nine weights sum to 1).
vec3 downsample13(sampler2D source, vec2 uv, vec2 t) {
    vec3 a = textureLod(source, uv + t * vec2(-2.0, -2.0), 0.0).rgb;
    vec3 b = textureLod(source, uv + t * vec2(0.0, -2.0), 0.0).rgb;
    vec3 c = textureLod(source, uv + t * vec2(2.0, -2.0), 0.0).rgb;
    vec3 d = textureLod(source, uv + t * vec2(-2.0, 0.0), 0.0).rgb;
    vec3 e = textureLod(source, uv, 0.0).rgb;
    vec3 f = textureLod(source, uv + t * vec2(2.0, 0.0), 0.0).rgb;
    vec3 g = textureLod(source, uv + t * vec2(-2.0, 2.0), 0.0).rgb;
    vec3 h = textureLod(source, uv + t * vec2(0.0, 2.0), 0.0).rgb;
    vec3 i = textureLod(source, uv + t * vec2(2.0, 2.0), 0.0).rgb;
    vec3 j = textureLod(source, uv + t * vec2(-1.0, -1.0), 0.0).rgb;
    vec3 k = textureLod(source, uv + t * vec2(1.0, -1.0), 0.0).rgb;
    vec3 l = textureLod(source, uv + t * vec2(-1.0, 1.0), 0.0).rgb;
    vec3 m = textureLod(source, uv + t * vec2(1.0, 1.0), 0.0).rgb;
    return finiteLight(e) * 0.125 +
           (finiteLight(a) + finiteLight(c) + finiteLight(g) + finiteLight(i)) * 0.03125 +
           (finiteLight(b) + finiteLight(d) + finiteLight(f) + finiteLight(h)) * 0.0625 +
           (finiteLight(j) + finiteLight(k) + finiteLight(l) + finiteLight(m)) * 0.125;
}

// The 3x3 tent (1 2 1 / 2 4 2 / 1 2 1, over 16) one texel of the coarser level `t` apart.
vec3 upsampleTent(sampler2D source, vec2 uv, vec2 t) {
    vec3 sum = textureLod(source, uv, 0.0).rgb * 4.0;
    sum += (textureLod(source, uv + vec2(-t.x, 0.0), 0.0).rgb +
            textureLod(source, uv + vec2(t.x, 0.0), 0.0).rgb +
            textureLod(source, uv + vec2(0.0, -t.y), 0.0).rgb +
            textureLod(source, uv + vec2(0.0, t.y), 0.0).rgb) * 2.0;
    sum += textureLod(source, uv + vec2(-t.x, -t.y), 0.0).rgb +
           textureLod(source, uv + vec2(t.x, -t.y), 0.0).rgb +
           textureLod(source, uv + vec2(-t.x, t.y), 0.0).rgb +
           textureLod(source, uv + vec2(t.x, t.y), 0.0).rgb;
    return sum / 16.0;
}

// The texel this invocation writes and its centre in the written image's [0, 1]^2; false outside.
bool texelOf(out ivec2 texel, out vec2 uv) {
    texel = ivec2(gl_GlobalInvocationID.xy);
    uv = (vec2(texel) + 0.5) / vec2(step.size.xy);
    return all(lessThan(gl_GlobalInvocationID.xy, step.size.xy));
}

#endif
