// Push constants of the trajectory effect passes (render/trail_effect_pass.h and the kinds'
// passes; shaders/effect_*.vert/.geom/.frag): how trajectory vertices are drawn.
#ifndef MFX_SHARED_EFFECT_DRAW_H
#define MFX_SHARED_EFFECT_DRAW_H

#include "common.h"

MFX_SHARED_BEGIN

struct EffectDraw {
    vec4 timing; // x: the frame's time (s); y: the trail's lifetime (s); z: width or size (world
                 // units); w: the segment's dt (s), for the age of a sample along it
    vec4 tint;   // rgb multiplies the vertex colour; a multiplies its alpha
    // The look (scene::RibbonLook of speed-lines and particles, scene::VolumeLook of the lit
    // volumes): x 1 = colour over life; y 1 = width (particles: size) over life; z 1 = additive;
    // w: lines 1 = facing the blade's plane, volumes 1 = life is the place along the sweep
    // (position.w) rather than the age. In push constants, not the style's uniform buffer, so
    // that no branch depends on a uniform buffer (lavapipe compiles a shader variant per value of
    // such).
    vec4 ribbonFlags;
    vec4 ribbonLight; // x: intensity; y: core whiteness; z 1 = tube; w: depth fade (world units)
    vec4 rimLight;    // volumes: x the Fresnel rim's strength, yzw its colour (linear RGB)
    // Lines: x 1 = each vertex's direction along its line comes from the joins buffer (binding 3,
    // ribbon_joins.comp), so the pieces that meet at a sample share its edge points; 0 = each
    // piece's own direction (a ribbon without joins). y: sheets, S + 1 (the samples of a line in a
    // segment; effect_sheet.vert).
    vec4 ribbonShape;
    // Speed-lines' texture (shaders/render/ribbon_texture.glsl; scene::RibbonTexture): x the UV
    // mode, 0 none, 1 stretch, 2 per segment, 3 tiled, 4 distance; y u per unit of the mode's
    // measure (stretch: 1 / the live ribbon's age span; tiled: repeats / lifetime; distance: 1 /
    // tile length); z the scroll's u offset now, in [0, 1), exactly 0 without scrolling; w the
    // erosion's soft edge (0: no erosion).
    vec4 ribbonTexture;
};

// Push constants of ribbon_joins.comp: the live segments of one speed-line queue, chained.
#define MFX_RIBBON_JOINS_GROUP_SIZE 64
struct RibbonJoinConstants {
    uint sourceVertices; // lines per segment
    uint perLine;        // S + 1 samples of each line in a segment
    uint segments;       // live segments, newest first, in the chain buffer
    uint pad0;
};

// Push constants of ribbon_distance.comp: the segments of one speed-line queue whose samples'
// distances along their lines are still to be found, oldest first.
#define MFX_RIBBON_DISTANCE_GROUP_SIZE 64
#define MFX_RIBBON_NO_SEGMENT 0xffffffffu
struct RibbonDistanceConstants {
    uint sourceVertices; // lines per segment
    uint perLine;        // S + 1 samples of each line in a segment
    uint segments;       // entries of the list
    uint pad0;
};

// How a speed-line ribbon or a particle looks over its life (scene::RibbonLook; uniform buffer,
// std140, binding 1 of the speed-line and particle programs). Stop i's position is
// colourAt[i / 4][i % 4], and so on; all MFX_RIBBON_MAX_STOPS stops are filled, those past the
// last given repeating it at life 1.
#define MFX_RIBBON_MAX_STOPS 8
struct RibbonStyle {
    vec4 colours[MFX_RIBBON_MAX_STOPS]; // RGBA by life
    vec4 colourAt[2];
    vec4 widths[2]; // the width's factor by life
    vec4 widthAt[2];
    vec4 erosion[2]; // the texture's erosion threshold by life (all 0: none)
    vec4 erosionAt[2];
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(EffectDraw, 112);
MFX_CHECK_LAYOUT(EffectDraw, ribbonTexture, 96);
MFX_CHECK_LAYOUT(EffectDraw, ribbonShape, 80);
MFX_CHECK_SIZE(RibbonJoinConstants, 16);
MFX_CHECK_SIZE(RibbonDistanceConstants, 16);
MFX_CHECK_LAYOUT(EffectDraw, rimLight, 64);
MFX_CHECK_LAYOUT(EffectDraw, ribbonLight, 48);
MFX_CHECK_SIZE(RibbonStyle, 288);
MFX_CHECK_LAYOUT(RibbonStyle, erosionAt, 256);
MFX_CHECK_LAYOUT(RibbonStyle, colourAt, 128);
MFX_CHECK_LAYOUT(RibbonStyle, widthAt, 192);
#endif

#endif
