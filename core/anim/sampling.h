// Sampling clips: one channel at a time (glTF 2.0 interpolation: LINEAR with slerp for rotations,
// STEP, CUBICSPLINE Hermite), a whole pose, and the joint matrices of a skin.
#pragma once

#include "core/anim/character.h"

#include <vector>

namespace mfx::anim {

// How a clip time outside [0, duration] is brought back: wrapped round, or held at the ends.
enum class Wrap { Loop, Clamp };

// The clip time at which `clip` is sampled for a playback time `time`.
float clipTime(const Clip& clip, float time, Wrap wrap);

// A channel's value at clip time t: before the first key the first value, after the last key the
// last value. Rotations come back as unit quaternions in (x, y, z, w) order.
glm::vec4 sampleChannel(const Channel& channel, float t);

struct Pose {
    std::vector<Transform> local; // per node
    std::vector<glm::mat4> world; // per node: parent's world * local
};

// The rest pose (no clip) or `clip` at playback time `time`.
Pose samplePose(const Character& character, const Clip* clip, float time, Wrap wrap = Wrap::Loop);

// A pose given as every node's world matrix (a host's animation): the local transforms follow
// from the parents' (each local matrix split into translation, rotation and scale; shear is
// dropped). `world` holds one matrix per node.
Pose poseFromWorld(const Character& character, std::vector<glm::mat4> world);

// The pose a fraction `s` of the way from `a` to `b`, node by node in local space: translations
// and scales blended linearly, rotations by slerp along the shorter arc, so a limb swung between
// the two moves on an arc about its joint. Both poses must hold every node.
Pose interpolatePose(const Character& character, const Pose& a, const Pose& b, float s);

// Joint matrices of skin `skin` in `pose`: world(joint) * inverseBind(joint), in the skin's joint
// order (the skinned mesh's own node transform is ignored, as glTF says).
std::vector<glm::mat4> jointMatrices(const Character& character, int skin, const Pose& pose);

} // namespace mfx::anim
