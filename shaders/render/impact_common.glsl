// What the impact's draws share (impact.vert, impact.frag): the frame, the sparks' look over life
// (ribbon_style.glsl, binding 1), the scene's depth (depth_fade.glsl, binding 2), and the draw.
#ifndef MFX_IMPACT_COMMON_GLSL
#define MFX_IMPACT_COMMON_GLSL

#include "shared/impact.h"
#include "shared/scene_draw.h"

layout(std140, binding = 0) uniform Frame {
    SceneFrame frame;
};
layout(push_constant) uniform Draw {
    ImpactDraw draw;
};

#endif
