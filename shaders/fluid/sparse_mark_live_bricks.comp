// The active set's rebuild, 1: every active brick with a live cell (pigment alpha or cell-centre
// speed above the thresholds, as measure_activity.comp measures them; NaN and Inf count as live)
// is wanted. Twin: SparseBricks::wantCell for each live cell.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_common.glsl"

layout(std140, binding = 3) uniform Rebuild {
    SparseRebuildParameters rebuild;
};
layout(std430, binding = 4) readonly buffer VelocityX {
    float velocityX[];
};
layout(std430, binding = 5) readonly buffer VelocityY {
    float velocityY[];
};
layout(std430, binding = 6) readonly buffer VelocityZ {
    float velocityZ[];
};
layout(std430, binding = 7) readonly buffer Pigment {
    vec4 pigment[];
};
layout(std430, binding = 8) buffer Wanted {
    uint wanted[];
};

shared uint live;

void main() {
    if (gl_LocalInvocationIndex == 0u) live = 0u;
    barrier();
    BrickCell at = listedCell();
    ivec3 l = at.local;
    uint s = at.slot;
    float alpha = abs(pigment[cellElementIn(s, l)].a);
    vec3 u = 0.5 * vec3(velocityX[faceElementIn(s, 0, l)] + velocityX[faceElementIn(s, 0, l + ivec3(1, 0, 0))],
                        velocityY[faceElementIn(s, 1, l)] + velocityY[faceElementIn(s, 1, l + ivec3(0, 1, 0))],
                        velocityZ[faceElementIn(s, 2, l)] + velocityZ[faceElementIn(s, 2, l + ivec3(0, 0, 1))]);
    float speed = length(u);
    bool bad = isnan(alpha) || isinf(alpha) || isnan(speed) || isinf(speed);
    if (bad || alpha > rebuild.thresholds.x || speed > rebuild.thresholds.y) live = 1u;
    barrier();
    if (gl_LocalInvocationIndex == 0u && live != 0u) {
        ivec3 n = brickCount();
        wanted[at.brick.x + n.x * (at.brick.y + n.y * at.brick.z)] = MFX_BRICK_WANTED;
    }
}
