// The flipbook player's push constants (shaders/render/flipbook_player.*, render/flipbook.h;
// docs/flipbook.md): which sheet layout, which cell position, how the motion is scaled.
#ifndef MFX_SHARED_FLIPBOOK_H
#define MFX_SHARED_FLIPBOOK_H

#include "common.h"

MFX_SHARED_BEGIN

struct FlipbookPlay {
    vec4 grid;     // columns, rows, cells used, motion scale (0: a plain cross-fade)
    vec4 playhead; // x: the position in cells (cell index + fraction); y: 1 to loop (wrap past the
                   // last cell to the first), 0 to hold the last cell; zw unused
    vec4 quad;     // the quad in clip space: x0, y0, x1, y1 (+y up); uv (0, 0) at (x0, y1)
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(FlipbookPlay, 48);
MFX_CHECK_LAYOUT(FlipbookPlay, playhead, 16);
MFX_CHECK_LAYOUT(FlipbookPlay, quad, 32);
#endif

#endif
