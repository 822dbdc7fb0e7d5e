// bloomUpsample: the pyramid summed from the coarsest level up: a level's own down-sampled
// picture plus the tent-filtered sum of every coarser level (Jimenez 2014; bloom_common.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "bloom_common.glsl"

layout(binding = 0) uniform sampler2D coarser; // the sum of the coarser levels
layout(binding = 1) uniform sampler2D own;     // this level's down-sample
layout(rgba16f, binding = 2) uniform writeonly image2D sum;

void main() {
    ivec2 texel;
    vec2 uv;
    if (!texelOf(texel, uv)) return;
    vec3 colour = textureLod(own, uv, 0.0).rgb + upsampleTent(coarser, uv, 1.0 / vec2(step.size.zw));
    imageStore(sum, texel, vec4(colour, 1.0));
}
