// Structures of the smoke pass (render/smoke_pass.h): the pigment bounds found on the GPU
// (shaders/render/pigment_bounds.comp) and the push constants of the march and the composite
// (shaders/render/smoke.vert, smoke_march.glsl, smoke_composite.frag).
#ifndef MFX_SHARED_SMOKE_DRAW_H
#define MFX_SHARED_SMOKE_DRAW_H

#include "common.h"

// Workgroup shape of pigment_bounds.comp, x fastest as the grid's cells.
#define MFX_PIGMENT_BOUNDS_GROUP_X 8
#define MFX_PIGMENT_BOUNDS_GROUP_Y 8
#define MFX_PIGMENT_BOUNDS_GROUP_Z 4

// The distance the fluid buffer is cleared to where no ray was marched (outside the pigment's box,
// so no smoke): the composite counts such texels as matching every pixel.
#define MFX_SMOKE_NO_DISTANCE (-1.0e30)

MFX_SHARED_BEGIN

// The box of cells whose pigment alpha exceeds the threshold (storage buffer, std430). Reset to
// low = 0xffffffff, high = 0 before each search, so low.x > high.x means no pigment.
struct PigmentBounds {
    uvec4 low;  // xyz: lowest cell index with pigment; w: unused
    uvec4 high; // xyz: highest cell index with pigment; w: unused
};

// Push constants of pigment_bounds.comp.
struct PigmentBoundsDispatch {
    uvec4 size;      // xyz: cells of the grid; w: unused
    float threshold; // a cell counts when its alpha exceeds this
    float pad0;
    float pad1;
    float pad2;
};

// Push constants of the march and the composite.
struct SmokeDraw {
    mat4 inverseViewProjection; // clip (Vulkan depth 0..1) to world
    vec4 gridOrigin;            // xyz: world position of the grid's low corner; w: cell size
    vec4 gridSize;              // xyz: cells; w: march steps per cell
    vec4 eye;                   // xyz: camera position; w: depth-fade distance b (world units)
    vec4 light;                 // xyz: unit vector towards the key light; w: density scale
};

// SmokeStyle::params.w values (scene::SmokePreset).
#define MFX_SMOKE_PRESET_SMOKE 0.0
#define MFX_SMOKE_PRESET_FIRE 1.0
#define MFX_SMOKE_PRESET_ENERGY 2.0
#define MFX_SMOKE_PRESET_CARTOON 3.0

// How the march shades one volume (uniform buffer, std140, binding 3 of smoke_march.glsl and of
// smoke_cartoon_composite.frag).
struct SmokeStyle {
    vec4 ramp[4]; // rgb: the colour at pigment alpha w (rising); used by fire and energy. The
                  // cartoon look: band k's colour (linear), shadow first
    vec4 params;  // x: glow (emitted light at full density; cartoon: rim); y: cel bands (0:
                  // smooth; cartoon: its bands); z: key light intensity; w: MFX_SMOKE_PRESET_*
    vec4 light;   // rgb: the key light's colour; w: the phase function's anisotropy g
    // The cartoon look (scene::CartoonSmoke; shaders/render/smoke_cartoon.glsl):
    vec4 surface; // x: threshold; y: billow; z: billow scale (m); w: the billows' phase (time x
                  // billow speed)
    vec4 outline; // rgb: ink colour (linear); w: width (pixels of the picture)
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(PigmentBounds, 32);
MFX_CHECK_LAYOUT(PigmentBounds, high, 16);
MFX_CHECK_SIZE(PigmentBoundsDispatch, 32);
MFX_CHECK_LAYOUT(PigmentBoundsDispatch, threshold, 16);
MFX_CHECK_SIZE(SmokeDraw, 128);
MFX_CHECK_LAYOUT(SmokeDraw, gridOrigin, 64);
MFX_CHECK_LAYOUT(SmokeDraw, light, 112);
MFX_CHECK_SIZE(SmokeStyle, 128);
MFX_CHECK_LAYOUT(SmokeStyle, params, 64);
MFX_CHECK_LAYOUT(SmokeStyle, surface, 96);
MFX_CHECK_LAYOUT(SmokeStyle, outline, 112);
#endif

#endif
