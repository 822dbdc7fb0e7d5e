// The smoke pass's box: the box of cells that hold pigment (found on the GPU by
// shaders/render/pigment_bounds.comp), grown by one cell as trilinear samples reach that far,
// clamped to the grid, in world units. The box's faces (smoke.vert) and the march
// (smoke_march.comp) take it from here.
#ifndef MFX_SMOKE_BOX_GLSL
#define MFX_SMOKE_BOX_GLSL

#include "shared/smoke_draw.h"

// False for an empty box (no cell holds pigment).
bool pigmentBox(SmokeDraw d, PigmentBounds b, out vec3 low, out vec3 high) {
    vec3 cells = d.gridSize.xyz;
    vec3 lowCell = max(vec3(b.low.xyz) - 1.0, vec3(0.0));
    vec3 highCell = min(vec3(b.high.xyz) + 2.0, cells);
    low = d.gridOrigin.xyz + d.gridOrigin.w * lowCell;
    high = d.gridOrigin.xyz + d.gridOrigin.w * highCell;
    return b.low.x <= b.high.x;
}

#endif
