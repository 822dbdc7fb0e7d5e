// The active set's rebuild, 1: every active brick with a live cell (pigment alpha or cell-centre
// speed above the thresholds, as measure_activity.comp measures them; NaN and Inf count as live)
// is wanted. Twin: SparseBricks::wantCell for each live cell. The bricks with live pigment are
// counted (a grid with solids settles on its pigment alone: SparseSmokeSolver::finishFrame).
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
// The rebuild's counts: [0] the refused bricks (sparse_allocate_bricks.comp), [1] the bricks with
// live pigment.
layout(std430, binding = 9) buffer Counts {
    uint counts[];
};

shared uint live;
shared uint livePigment;

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        live = 0u;
        livePigment = 0u;
    }
    barrier();
    BrickCell at = listedCell();
    ivec3 l = at.local;
    uint s = at.slot;
    float alpha = abs(pigment[cellElementIn(s, l)].a);
    vec3 u = 0.5 * vec3(velocityX[faceElementIn(s, 0, l)] + velocityX[faceElementIn(s, 0, l + ivec3(1, 0, 0))],
                        velocityY[faceElementIn(s, 1, l)] + velocityY[faceElementIn(s, 1, l + ivec3(0, 1, 0))],
                        velocityZ[faceElementIn(s, 2, l)] + velocityZ[faceElementIn(s, 2, l + ivec3(0, 0, 1))]);
    float speed = length(u);
    bool badAlpha = isnan(alpha) || isinf(alpha);
    bool bad = badAlpha || isnan(speed) || isinf(speed);
    if (bad || alpha > rebuild.thresholds.x || speed > rebuild.thresholds.y) live = 1u;
    if (badAlpha || alpha > rebuild.thresholds.x) livePigment = 1u;
    barrier();
    if (gl_LocalInvocationIndex == 0u && live != 0u) {
        ivec3 n = brickCount();
        wanted[at.brick.x + n.x * (at.brick.y + n.y * at.brick.z)] = MFX_BRICK_WANTED;
        // Each of the brick's two workgroups counts; the host only asks whether any did.
        if (livePigment != 0u) atomicAdd(counts[1], 1u);
    }
}
