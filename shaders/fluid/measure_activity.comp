// measureActivity: how much is still going on in the grid, for the solver to decide whether it
// may sleep: the largest pigment alpha and the largest speed at a cell centre (the mean of its two
// faces per component), atomically maximised into two uints (non-negative floats order like their
// bit patterns). The buffer is cleared before the dispatch. A diagnostic, not a solver stage.
// CPU counterpart: fluid::activity (fluid/smoke_solver.cpp), from a FieldState.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityX;
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityY;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityZ;
layout(binding = 4, MFX_PIGMENT_FORMAT) uniform readonly image3D pigment;
layout(std430, binding = 5) buffer Activity {
    uint largestAlpha;
    uint largestSpeed;
};

void main() {
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(q, cellCount()))) return;
    float alpha = abs(imageLoad(pigment, q).a);
    vec3 u = 0.5 * vec3(imageLoad(velocityX, q).r + imageLoad(velocityX, q + ivec3(1, 0, 0)).r,
                        imageLoad(velocityY, q).r + imageLoad(velocityY, q + ivec3(0, 1, 0)).r,
                        imageLoad(velocityZ, q).r + imageLoad(velocityZ, q + ivec3(0, 0, 1)).r);
    float speed = length(u);
    // NaN counts as activity: a blown-up field must not put the solver to sleep.
    if (isnan(alpha) || isinf(alpha)) alpha = 3.0e38;
    if (isnan(speed) || isinf(speed)) speed = 3.0e38;
    atomicMax(largestAlpha, floatBitsToUint(alpha));
    atomicMax(largestSpeed, floatBitsToUint(speed));
}
