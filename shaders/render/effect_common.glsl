// What every effect pass reads from a trajectory vertex (shared/trajectory.h): its alpha is the
// attenuation along the segment (stored) times a fade with the sample's age at draw time,
// 1 - age / lifetime (Xu et al., Algorithm 1; docs/architecture.md "One frame").
#ifndef MFX_EFFECT_COMMON_GLSL
#define MFX_EFFECT_COMMON_GLSL

#include "shared/effect_draw.h"
#include "shared/scene_draw.h"

layout(std140, binding = 0) uniform Frame {
    SceneFrame frame;
};
layout(push_constant) uniform Draw {
    EffectDraw draw;
};

// The sample's time is stored in normal.w (birth - tau * dt).
float ageFade(float sampleTime) {
    float age = draw.timing.x - sampleTime;
    return clamp(1.0 - age / max(draw.timing.y, 1e-6), 0.0, 1.0);
}

#endif
