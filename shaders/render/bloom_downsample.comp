// bloomDownsample: one level of the bloom's pyramid from the level above it (or the picture),
// half its width and height, by the 13-tap filter (bloom_common.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "bloom_common.glsl"

layout(binding = 0) uniform sampler2D source;
layout(rgba16f, binding = 1) uniform writeonly image2D level;

void main() {
    ivec2 texel;
    vec2 uv;
    if (!texelOf(texel, uv)) return;
    vec3 colour = downsample13(source, uv, 1.0 / vec2(step.size.zw));
    imageStore(level, texel, vec4(colour, 1.0));
}
