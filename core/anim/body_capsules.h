// The body as capsules, one per joint that carries vertices (and one per rigid part): the cheap
// stand-in for the skinned mesh that the smoke flows around (docs/fluid.md, "Solids"). Fitted
// once, in the bind pose, to the vertices each joint moves most; posed every frame by the joint's
// world matrix, so a capsule follows its bone exactly and its ends' motion over a step is the
// body's there.
//
// Why capsules and not the mesh voxelised every step: a capsule per bone is a closed solid by
// construction (a skinned mesh need not be: open sleeves, separate eyes, flat-shaded seams that
// break an inside-outside parity test), its inside test is a few operations per cell and solid
// (no rasterisation, no flood fill), and the velocity of any point inside it follows from its
// two ends. The price is shape: a capsule rounds a hand or a foot off, and a joint's blend
// region is covered by the two capsules' overlap.
#pragma once

#include "core/anim/character.h"
#include "core/anim/sampling.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace mfx::anim {

struct BodyCapsule {
    int node = -1;     // the node whose world matrix carries it
    glm::vec3 a{0.0f}; // the axis' ends in the node's space (equal: a sphere)
    glm::vec3 b{0.0f};
    float radius = 0.0f;   // in the node's space
    uint32_t vertices = 0; // the vertices it was fitted to
};

// A capsule in the world of one pose.
struct PosedCapsule {
    glm::vec3 a{0.0f}, b{0.0f};
    float radius = 0.0f;
};

// One capsule per node that carries vertices: a skinned vertex belongs to the joint with its
// largest weight (taken into the joint's space by its inverse bind matrix), a rigid primitive's
// vertices to its node. The axis is the principal axis of the node's vertices (their covariance's
// largest eigenvector), the radius the `radiusQuantile` quantile of their distances from it (1:
// the farthest; below 1 leaves the outliers a neighbouring capsule usually covers), and the ends
// those of the shortest axis whose round caps still hold every point within the radius. Unskinned
// geometry on no node is static and left out.
std::vector<BodyCapsule> fitBodyCapsules(const Character& character, float radiusQuantile = 0.95f);

// `capsule` where `pose` puts its node; the radius scaled by the cube root of the world matrix's
// volume scale.
PosedCapsule poseCapsule(const BodyCapsule& capsule, const Pose& pose);

// Distance from p to the capsule's surface: negative inside.
float signedDistance(const PosedCapsule& capsule, glm::vec3 p);

} // namespace mfx::anim
