// Push constants of the effect passes (render/kinds/effect_pass.h;
// shaders/effect_*.vert/.geom/.frag): how trajectory vertices are drawn.
#ifndef MFX_SHARED_EFFECT_DRAW_H
#define MFX_SHARED_EFFECT_DRAW_H

#include "common.h"

MFX_SHARED_BEGIN

struct EffectDraw {
    vec4 timing; // x: the frame's time (s); y: the trail's lifetime (s); z: width or size (world
                 // units); w: the segment's dt (s), for the age of a sample along it
    vec4 tint;   // rgb multiplies the vertex colour; a multiplies its alpha
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(EffectDraw, 32);
#endif

#endif
