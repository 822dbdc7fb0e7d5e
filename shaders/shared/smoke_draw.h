// Push constants of the smoke pass (render/smoke_pass.h, shaders/smoke.vert/.frag).
#ifndef MFX_SHARED_SMOKE_DRAW_H
#define MFX_SHARED_SMOKE_DRAW_H

#include "common.h"

MFX_SHARED_BEGIN

struct SmokeDraw {
    mat4 inverseViewProjection; // clip (Vulkan depth 0..1) to world
    vec4 gridOrigin;            // xyz: world position of the grid's low corner; w: cell size
    vec4 gridSize;              // xyz: cells; w: march steps per cell
    vec4 eye;                   // xyz: camera position; w: depth-fade distance b (world units)
    vec4 light;                 // xyz: unit vector towards the key light; w: density scale
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(SmokeDraw, 128);
#endif

#endif
