// Structures of the scene pass (render/character_pass.h, shaders/render/character.vert/.frag),
// shared by GLSL and C++.
#ifndef MFX_SHARED_SCENE_DRAW_H
#define MFX_SHARED_SCENE_DRAW_H

#include "common.h"

MFX_SHARED_BEGIN

// Uniform buffer, std140: the camera and the key light of a frame.
struct SceneFrame {
    mat4 viewProjection;
    vec4 cameraPosition;      // xyz world
    vec4 lightDirection;      // xyz unit vector from the surface towards the light
    vec4 lightColor;          // rgb linear radiance times intensity; w: ambient fraction
    vec4 sky;                 // rgb: ambient colour from above; w: specular strength
    vec4 ground;              // rgb: ambient colour from below; w: specular exponent
    mat4 lightViewProjection; // world to the key light's shadow map (clip space)
    vec4 shadow;              // x: 1 when the shadow map is used; y: depth bias; z: 1 / its size
    vec4 depthRange;          // x, y: the camera's near and far planes (depth_fade.glsl)
};

// SceneObject::style.x values.
#define MFX_STYLE_LIT 0.0
#define MFX_STYLE_TOON 1.0

// Push constants, one per draw.
struct SceneObject {
    mat4 model;     // identity for skinned geometry (already in world space)
    vec4 baseColor; // linear RGB; a: 1
    vec4 style;     // x: MFX_STYLE_*; toon: y = ramp levels, z = rim strength; w: unused
};

// Push constants of the toon outline (shaders/render/outline.vert, .frag).
struct OutlineDraw {
    vec4 colour; // linear RGB; a: 1
    vec4 width;  // x: pixels; yz: 2 / the target's width and height (pixels to clip units)
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(SceneFrame, 240);
MFX_CHECK_LAYOUT(SceneFrame, depthRange, 224);
MFX_CHECK_LAYOUT(SceneFrame, lightViewProjection, 144);
MFX_CHECK_LAYOUT(SceneFrame, shadow, 208);
MFX_CHECK_LAYOUT(SceneFrame, cameraPosition, 64);
MFX_CHECK_LAYOUT(SceneFrame, lightColor, 96);
MFX_CHECK_LAYOUT(SceneFrame, ground, 128);
MFX_CHECK_SIZE(SceneObject, 96);
MFX_CHECK_LAYOUT(SceneObject, style, 80);
MFX_CHECK_SIZE(OutlineDraw, 32);
MFX_CHECK_LAYOUT(OutlineDraw, width, 16);
#endif

#endif
