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

// How a speed-line ribbon looks over its life (scene::RibbonLook; uniform buffer, std140, binding
// 1 of the speed-line program). Stop i's position is colourAt[i / 4][i % 4], and so on.
#define MFX_RIBBON_MAX_STOPS 8
struct RibbonStyle {
    vec4 colours[MFX_RIBBON_MAX_STOPS]; // RGBA by life
    vec4 colourAt[2];
    vec4 widths[2]; // the width's factor by life
    vec4 widthAt[2];
    vec4 counts; // x: colour stops (0: the trail's colour, faded with age); y: width stops (0: the
                 // built-in taper); z: intensity; w: core whiteness
    vec4 blend;  // x: 1 additive, 0 alpha
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(EffectDraw, 32);
MFX_CHECK_SIZE(RibbonStyle, 256);
MFX_CHECK_LAYOUT(RibbonStyle, colourAt, 128);
MFX_CHECK_LAYOUT(RibbonStyle, counts, 224);
#endif

#endif
