// bloomComposite: the picture replaced in place by mix(picture, bloom, strength), where the bloom
// is the sum of the pyramid's levels (bilinearly up-sampled from the finest, which the sum has
// already made smooth: one fetch a pixel rather than the tent's nine) divided by their number,
// so it has the picture's mean: the mix keeps the picture's total light (bloom_common.glsl).
// Alpha is kept.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "bloom_common.glsl"

layout(binding = 0) uniform sampler2D levels; // the summed pyramid at its finest level
layout(rgba16f, binding = 1) uniform image2D picture;

void main() {
    ivec2 texel;
    vec2 uv;
    if (!texelOf(texel, uv)) return;
    vec4 own = imageLoad(picture, texel);
    own.rgb = finiteLight(own.rgb);
    vec3 bloom = textureLod(levels, uv, 0.0).rgb * step.weights.y;
    imageStore(picture, texel, vec4(mix(own.rgb, bloom, step.weights.x), own.a));
}
