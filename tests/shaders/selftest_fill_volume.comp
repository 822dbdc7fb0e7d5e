// Self-test: writes a known pattern into a 3D storage image (r32f), one texel per invocation.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/selftest.h"

layout(local_size_x = MFX_FILL_VOLUME_GROUP_SIZE, local_size_y = MFX_FILL_VOLUME_GROUP_SIZE,
       local_size_z = MFX_FILL_VOLUME_GROUP_SIZE) in;

layout(binding = 0, r32f) uniform writeonly image3D volume;

layout(push_constant) uniform Constants {
    FillVolumeConstants constants;
};

// Scales the pattern: specialization constant 0 (default 1), to test specialization.
layout(constant_id = 0) const float patternScale = 1.0;

void main() {
    uvec3 p = gl_GlobalInvocationID;
    if (any(greaterThanEqual(p, constants.size.xyz))) return;
    float value = (float(p.x) + 1000.0 * float(p.y) + 1000000.0 * float(p.z)) * patternScale +
                  constants.offset;
    imageStore(volume, ivec3(p), vec4(value));
}
