// Structures of the passes after the scene is drawn: the bloom (render/bloom_pass.h,
// shaders/render/bloom_*.comp) and the tone map (render/tone_map_pass.h,
// shaders/render/tone_map.frag).
#ifndef MFX_SHARED_POST_H
#define MFX_SHARED_POST_H

#include "common.h"

// Workgroup shape of the bloom's compute shaders (one invocation a texel).
#define MFX_BLOOM_GROUP_X 8
#define MFX_BLOOM_GROUP_Y 8

// ToneMapDraw::toneMap values (scene::ToneMap).
#define MFX_TONE_MAP_NONE 0
#define MFX_TONE_MAP_ACES 1

MFX_SHARED_BEGIN

// Push constants of the bloom's down-sample, up-sample and composite steps.
struct BloomStep {
    uvec4 size;   // xy: texels of the image written; zw: texels of the image read
    vec4 weights; // composite: x = strength, y = 1 / levels; up-sample: x = 1 (add the level)
};

// Push constants of the tone map.
struct ToneMapDraw {
    float exposureScale; // 2^exposure
    uint toneMap;        // MFX_TONE_MAP_*
    float pad0;
    float pad1;
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(BloomStep, 32);
MFX_CHECK_LAYOUT(BloomStep, weights, 16);
MFX_CHECK_SIZE(ToneMapDraw, 16);
MFX_CHECK_LAYOUT(ToneMapDraw, toneMap, 4);
#endif

#endif
