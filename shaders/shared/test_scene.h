// Structures of the lit test scene (test_scene.vert/.frag): a camera/light uniform block and a
// per-object push constant block.
#ifndef MFX_SHARED_TEST_SCENE_H
#define MFX_SHARED_TEST_SCENE_H

#include "common.h"

MFX_SHARED_BEGIN

// Uniform buffer, std140.
struct TestSceneFrame {
    mat4 viewProjection;
    vec4 cameraPosition; // xyz world position
    vec4 lightDirection; // xyz unit vector from the surface towards the light
    vec4 lightColor;     // rgb linear radiance scale; w: ambient fraction
    vec4 specular;       // x: strength, y: Blinn-Phong exponent
};

// Push constants, one per draw.
struct TestSceneObject {
    mat4 model;
    vec4 baseColor; // linear RGB, a = 1
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(TestSceneFrame, 128);
MFX_CHECK_LAYOUT(TestSceneFrame, cameraPosition, 64);
MFX_CHECK_LAYOUT(TestSceneFrame, lightDirection, 80);
MFX_CHECK_LAYOUT(TestSceneFrame, lightColor, 96);
MFX_CHECK_LAYOUT(TestSceneFrame, specular, 112);
MFX_CHECK_SIZE(TestSceneObject, 80);
MFX_CHECK_LAYOUT(TestSceneObject, baseColor, 64);
#endif

#endif
