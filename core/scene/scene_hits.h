// The hits of a scene's impact effects (core/scene/kinds/impact_effect.h): where the bones an
// impact follows land on another character's body, frame by frame.
//
// Each impact's bones (resolved by fitScene) carry body capsules (core/anim/body_capsules.h); the
// target's whole body is its capsules. Over each frame interval of the performance (the clips
// without hit-stops: both fighters freeze together during a hit-stop, so where and when the
// blows land does not change, only when they are shown), every attacker capsule is swept
// against every target capsule (anim::firstContact: sub-frame time, point, direction, speed);
// the earliest contact of the frame is the hit. A blow is one hit: the impact is armed again only
// once none of its capsules touches the target at a frame's start. An impact lands only inside
// its time window.
//
// Hits are then laid out in scene time: the k-th hit's hit-stop holds the clips for its
// holdFrames frames after the frame it lands in, delaying every later frame of the performance.
#pragma once

#include "core/anim/character.h"
#include "core/scene/kinds/impact_effect.h"
#include "core/scene/scene.h"

#include <span>
#include <vector>

namespace mfx::scene {

// The most hits a scene records (later ones are left out), and the most capsule pairs it tests
// over all its frames (a scene past it is refused: its impacts, targets and frames are too many).
constexpr size_t kMaxHits = 256;
constexpr uint64_t kMaxHitTests = 50'000'000;

// Every hit of the scene's impacts in time order (scene.hits must be empty: the performance is
// sampled without hit-stops). Effects' bones must be resolved (fitScene).
Result<std::vector<Hit>> findHits(const Scene& scene, std::span<const anim::Character> cast);

// The impact a hit belongs to, or null where the scene no longer has it (effects removed after
// the hits were found, as a benchmark of the characters alone does): every consumer of
// scene.hits asks through it.
const ImpactSpec* hitImpact(const Scene& scene, const Hit& hit);

// The camera's shake at scene time `time` (world units, added to its position and target): each
// hit of an impact with a "shake" jolts the camera along the blow and then jitters it, dying out
// as (1 - age / shake_seconds)^2. Zero without hits. Deterministic.
glm::vec3 cameraShake(const Scene& scene, float time);

} // namespace mfx::scene
