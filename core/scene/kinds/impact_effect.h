// The impact: what happens where a blow lands. Each hit of the effect's bones (on the character it
// follows) against another character's body (core/scene/scene_hits.h) spawns sparks (particles
// thrown along the blow and spread in a cone, under gravity and drag, drawn as streaks along their
// velocity), a flash at the contact point, a shockwave ring facing the camera or lying on the hit
// plane, and a burst of impulse and pigment into the smoke grids where it lands; the hit can
// hold both fighters' clips for a few frames (hit-stop) and shake the camera
// (render/kinds/impact_pass.h draws it).
#pragma once

#include "core/scene/effect_spec.h"
#include "core/scene/kinds/trail_effects.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace mfx::scene {

namespace detail {
class Object;
}

enum class RingFacing { None, Camera, HitPlane };

struct ImpactSpec : EffectKind<ImpactSpec> {
    static constexpr const char* kType = "impact";
    // Whom the blow can land on: a character's name; empty: every other character.
    std::string target;
    // Frames both fighters' clips hold after a hit while the effects go on (0: none).
    uint32_t hitStopFrames = 0;
    // The camera's shake after a hit: amplitude (world units) and how long it takes to die out.
    float shake = 0.0f;
    float shakeSeconds = 0.3f;

    // Sparks: how many a hit throws, their speed (m/s) along the blow's direction with a spread
    // (degrees either side of it), life (s), gravity (m/s^2, downwards) and linear drag (1/s),
    // the streak's width (m) and length (the distance the spark covers in `sparkStretch` s).
    uint32_t sparks = 24;
    float sparkSpeed = 6.0f;
    float sparkSpread = 55.0f;
    float sparkLife = 0.45f;
    float gravity = 9.81f;
    float drag = 2.5f;
    float sparkSize = 0.012f;
    float sparkStretch = 0.03f;
    RibbonLook look; // the sparks' colour and size over life, intensity, blend, depth fade

    // The flash: a glow at the contact point, `flashSize` across, over `flashSeconds`.
    float flashSize = 0.6f;
    float flashSeconds = 0.12f;
    glm::vec4 flashColour{1.0f, 0.9f, 0.6f, 1.0f};
    float flashIntensity = 4.0f;

    // The shockwave: a ring growing to `ringRadius` over `ringSeconds`, `ringWidth` wide.
    RingFacing ring = RingFacing::Camera;
    float ringRadius = 0.7f;
    float ringWidth = 0.05f;
    float ringSeconds = 0.25f;
    glm::vec4 ringColour{0.8f, 0.9f, 1.0f, 0.9f};

    // The smoke burst: into every smoke grid whose box holds the contact point, pushing the air
    // along the blow at `smokeImpulse` m/s (0: no burst) within `smokeRadius` of it, with pigment
    // `smokeColour`.
    float smokeImpulse = 6.0f;
    float smokeRadius = 0.15f;
    glm::vec4 smokeColour{1.0f, 0.8f, 0.5f, 1.0f};

    static std::vector<std::string> keys();
    static std::unique_ptr<EffectKindSpec> parse(const detail::Object& o);
    std::vector<std::pair<const char*, float*>> lengths() override {
        return {{"spark_size", &sparkSize},
                {"flash_size", &flashSize},
                {"ring_radius", &ringRadius},
                {"ring_width", &ringWidth},
                {"smoke_radius", &smokeRadius}};
    }
    bool showsAtRest() const override { return true; } // it shows where hits land, not motion
    bool fadesAgainstDepth() const override { return look.depthFade > 0.0f; }
};

// The longest an impact's sparks, flash or ring live (seconds): what a pass keeps a hit for.
float impactLifetime(const ImpactSpec& impact);

// A blow's unit direction (straight up where it has none) and two unit vectors across it: the
// frame its sparks' cone, its ring on the hit plane and its smoke burst are laid out in.
struct BlowAxes {
    glm::vec3 along{0.0f, 1.0f, 0.0f}, u{1.0f, 0.0f, 0.0f}, v{0.0f, 0.0f, 1.0f};
};
BlowAxes blowAxes(glm::vec3 direction);

// One spark as a hit throws it: from the contact point, at the hit's time.
struct SparkLaunch {
    glm::vec3 origin{0.0f};
    float time = 0.0f; // scene seconds
    glm::vec3 velocity{0.0f};
    float life = 0.0f; // seconds
};
// The sparks hit number `hitIndex` (its place in scene.hits, which seeds them) throws: each in a
// direction uniformly spread over the cone of half-angle spark_spread about the blow's direction,
// at spark_speed times 0.5-1.5, living spark_life times 0.6-1. Deterministic.
std::vector<SparkLaunch> impactSparks(const ImpactSpec& impact, glm::vec3 point,
                                      glm::vec3 direction, float time, uint32_t hitIndex);
// Where a spark thrown from `origin` at `velocity` is `t` seconds later, under `gravity` (m/s^2
// along -y) and linear drag `drag` (1/s): the closed form of dv/dt = g - drag v
// (shaders/render/impact_flight.glsl is its twin on the GPU).
glm::vec3 sparkPosition(glm::vec3 origin, glm::vec3 velocity, float gravity, float drag, float t);

} // namespace mfx::scene
