// The impact's sparks at the frame's time: each spark's streak, from where it was `stretch`
// seconds ago (never before its hit) to where it is now, on its closed-form flight path
// (impact_flight.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/impact.h"
#include "impact_flight.glsl"

layout(local_size_x = MFX_IMPACT_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer Sparks {
    ImpactSpark sparks[];
};
layout(std430, binding = 1) writeonly buffer Streaks {
    ImpactStreak streaks[];
};
layout(push_constant) uniform Constants {
    ImpactSparkConstants c;
};

void main() {
    if (gl_GlobalInvocationID.x >= c.count) return;
    uint i = c.first + gl_GlobalInvocationID.x;
    ImpactSpark s = sparks[i];
    float age = c.motion.x - s.origin.w;
    float life = max(s.velocity.w, 1e-6);
    float now = max(age, 0.0);
    float before = max(age - c.motion.w, 0.0);
    ImpactStreak streak;
    streak.head = vec4(sparkPosition(s.origin.xyz, s.velocity.xyz, c.motion.y, c.motion.z, now),
                       age / life);
    streak.tail = vec4(sparkPosition(s.origin.xyz, s.velocity.xyz, c.motion.y, c.motion.z, before),
                       0.0);
    streaks[i] = streak;
}
