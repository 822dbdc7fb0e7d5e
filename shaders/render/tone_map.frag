// toneMap: the picture's linear HDR colour, scaled by the exposure, mapped to [0, 1] and written
// to the sRGB output (which encodes it). The filmic curve is K. Narkowicz's fit of the ACES
// reference rendering and output transforms ("ACES Filmic Tone Mapping Curve", 2016):
//     f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14),
// applied to each channel. f(0) = 0, and f'(x) = (1.408 x^2 + 0.7028 x + 0.0042) / (...)^2 > 0, so
// it is monotonic; it reaches 1 at x = 7.24 and is clamped there. Without a tone map the colour is
// clamped to [0, 1], as an 8-bit target would.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/post.h"

layout(push_constant) uniform Draw {
    ToneMapDraw draw;
};
layout(binding = 0) uniform sampler2D picture; // the scene target's colour, same size

layout(location = 0) out vec4 outColor;

vec3 acesFit(vec3 x) {
    return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
}

void main() {
    // NaN to 0, infinity to the largest fp16, below 0 to 0.
    vec3 colour = texelFetch(picture, ivec2(gl_FragCoord.xy), 0).rgb;
    bvec3 bad = isnan(colour);
    colour = vec3(bad.x ? 0.0 : colour.x, bad.y ? 0.0 : colour.y, bad.z ? 0.0 : colour.z);
    colour = clamp(colour, 0.0, 65504.0);
    colour *= draw.exposureScale;
    if (draw.toneMap == MFX_TONE_MAP_ACES) colour = acesFit(colour);
    outColor = vec4(clamp(colour, 0.0, 1.0), 1.0);
}
