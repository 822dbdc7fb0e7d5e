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

// Joint matrices of skin `skin` in `pose`: world(joint) * inverseBind(joint), in the skin's joint
// order (the skinned mesh's own node transform is ignored, as glTF says).
std::vector<glm::mat4> jointMatrices(const Character& character, int skin, const Pose& pose);

} // namespace mfx::anim
