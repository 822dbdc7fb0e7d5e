// The built-in fighter: a skinned humanoid built in code, so that everything runs with no asset.
// 21 joints (hips root, spine, chest, neck, head; per side shoulder, upper arm, forearm, hand,
// thigh, shin, foot, toe), a body of smooth tubes in a two-colour outfit with skin-coloured head
// and hands, and a sword (its own mesh, "sword", bound to hand_r). Clips: idle, roundhouse_kick,
// straight_punch, sword_slash, spin, hit_react (struck from the front: knocked back, then the
// recovery, 0.75 s) and kick_slash (the roundhouse kick into the sword slash, 1.7 s). Y up,
// facing +z, metres; deterministic.
#pragma once

#include "core/anim/character.h"

namespace mfx::anim {

Character makeFighter();

} // namespace mfx::anim
