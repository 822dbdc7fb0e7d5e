// When and where two moving capsules first touch within a frame: the hit test of a blow (an
// attacker's bone capsule against another character's body capsules, core/anim/body_capsules.h).
// Each capsule's axis ends move in a straight line over the frame (from the previous pose to this
// one); the gap between the two (the distance between their axes less both radii) is sampled at
// even sub-steps fine enough that neither capsule moves more than half the two radii between
// samples, and the first sub-step where it closes is narrowed by bisection to the moment of
// contact. Capsules that already touch when the frame starts are not a new contact.
#pragma once

#include "core/anim/body_capsules.h"

#include <glm/glm.hpp>
#include <optional>

namespace mfx::anim {

// The closest points of segments [a0, a1] and [b0, b1]: p = a0 + s (a1 - a0), q = b0 + t (b1 - b0),
// s and t in [0, 1] (Ericson, "Real-Time Collision Detection", 2005, Sec. 5.1.9: the unclamped
// minimum of |p - q|^2 over (s, t), then each parameter clamped in turn). A degenerate segment is
// a point.
struct SegmentPoints {
    float s = 0.0f, t = 0.0f;
    glm::vec3 p{0.0f}, q{0.0f};
};
SegmentPoints closestPoints(glm::vec3 a0, glm::vec3 a1, glm::vec3 b0, glm::vec3 b1);

// A capsule at the start of a frame and at its end.
struct SweptCapsule {
    PosedCapsule from, to;
};

// The first contact of `attacker` with `target` within a frame of `seconds`.
struct CapsuleContact {
    float time = 0.0f;         // in [0, 1] of the frame
    glm::vec3 point{0.0f};     // on the attacker's surface, towards the target's axis
    glm::vec3 direction{0.0f}; // of the attacker's contact point relative to the target's
    float speed = 0.0f;        // that relative speed, world units per second
};
std::optional<CapsuleContact> firstContact(const SweptCapsule& attacker, const SweptCapsule& target,
                                           float seconds);

} // namespace mfx::anim
