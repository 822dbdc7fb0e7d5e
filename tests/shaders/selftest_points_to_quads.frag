// Self-test of the geometry stage: flat colour.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/selftest.h"

layout(location = 0) out vec4 outColor;

layout(push_constant) uniform Constants {
    PointsToQuadsConstants constants;
};

void main() {
    outColor = constants.color;
}
