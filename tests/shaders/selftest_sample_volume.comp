// Self-test: samples a 3D texture through a combined image sampler at given coordinates, so the
// hardware's trilinear filtering can be compared with the CPU's.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/selftest.h"

layout(local_size_x = 64) in;

layout(binding = 0) uniform sampler3D volume;
layout(std430, binding = 1) readonly buffer Coordinates {
    vec4 coordinates[];
};
layout(std430, binding = 2) writeonly buffer Results {
    float results[];
};

layout(push_constant) uniform Constants {
    SampleVolumeConstants constants;
};

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= constants.count) return;
    results[i] = textureLod(volume, coordinates[i].xyz, 0.0).r;
}
