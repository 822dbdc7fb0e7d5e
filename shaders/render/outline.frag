// The toon outline, fragment stage: one flat colour (outline.vert).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/scene_draw.h"

layout(push_constant) uniform Outline {
    OutlineDraw outline;
};

layout(location = 0) out vec4 outColor;

void main() {
    outColor = vec4(outline.colour.rgb, 1.0);
}
