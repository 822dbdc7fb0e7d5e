// Self-test: y = a*x + y over a storage buffer, `iterations` times. Checks compute dispatch,
// push constants, descriptor sets and readback element by element.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/selftest.h"

layout(local_size_x = MFX_SAXPY_GROUP_SIZE) in;

layout(std430, binding = 0) readonly buffer InputX {
    float x[];
};
layout(std430, binding = 1) buffer InputOutputY {
    float y[];
};

layout(push_constant) uniform Constants {
    SaxpyConstants constants;
};

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= constants.count) return;
    float value = y[i];
    for (uint k = 0; k < constants.iterations; ++k)
        value = constants.a * x[i] + value;
    y[i] = value;
}
