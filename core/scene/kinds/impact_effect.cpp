#include "core/scene/kinds/impact_effect.h"

#include "core/scene/json_object.h"

#include <algorithm>
#include <cmath>

namespace mfx::scene {

std::vector<std::string> ImpactSpec::keys() {
    std::vector<std::string> keys = {"target",       "hit_stop_frames",
                                     "shake",        "shake_seconds",
                                     "sparks",       "spark_speed",
                                     "spark_spread", "spark_life",
                                     "gravity",      "drag",
                                     "spark_size",   "spark_stretch",
                                     "flash_size",   "flash_seconds",
                                     "flash_colour", "flash_intensity",
                                     "ring",         "ring_radius",
                                     "ring_width",   "ring_seconds",
                                     "ring_colour",  "smoke_impulse",
                                     "smoke_radius", "smoke_colour"};
    for (const std::string& l : particleLookKeys())
        keys.push_back(l);
    return keys;
}

std::unique_ptr<EffectKindSpec> ImpactSpec::parse(const detail::Object& o) {
    auto s = std::make_unique<ImpactSpec>();
    // Checked against the scene's characters once they are all read (scene.cpp).
    s->target = o.characterName("target");
    s->hitStopFrames = o.integer("hit_stop_frames", s->hitStopFrames, 0, 60);
    s->shake = float(o.number("shake", s->shake, 0.0, 10.0));
    s->shakeSeconds = float(o.number("shake_seconds", s->shakeSeconds, 0.0, 10.0, true));
    s->sparks = o.integer("sparks", s->sparks, 0, 512);
    s->sparkSpeed = float(o.number("spark_speed", s->sparkSpeed, 0.0, 1000.0));
    s->sparkSpread = float(o.number("spark_spread", s->sparkSpread, 0.0, 180.0));
    s->sparkLife = float(o.number("spark_life", s->sparkLife, 0.0, 10.0, true));
    s->gravity = float(o.number("gravity", s->gravity, -1000.0, 1000.0));
    s->drag = float(o.number("drag", s->drag, 0.0, 1000.0));
    s->sparkSize = float(o.number("spark_size", s->sparkSize, 0.0, 1.0, true));
    s->sparkStretch = float(o.number("spark_stretch", s->sparkStretch, 0.0, 1.0));
    s->flashSize = float(o.number("flash_size", s->flashSize, 0.0, 100.0));
    s->flashSeconds = float(o.number("flash_seconds", s->flashSeconds, 0.0, 10.0, true));
    s->flashColour = o.colour("flash_colour", s->flashColour);
    s->flashIntensity = float(o.number("flash_intensity", s->flashIntensity, 0.0, 1000.0));
    const std::string ring =
        o.choice("ring", s->ring == RingFacing::Camera ? "camera" : "hit_plane",
                 {"camera", "hit_plane", "none"});
    s->ring = ring == "camera"      ? RingFacing::Camera
              : ring == "hit_plane" ? RingFacing::HitPlane
                                    : RingFacing::None;
    s->ringRadius = float(o.number("ring_radius", s->ringRadius, 0.0, 100.0, true));
    s->ringWidth = float(o.number("ring_width", s->ringWidth, 0.0, 10.0, true));
    s->ringSeconds = float(o.number("ring_seconds", s->ringSeconds, 0.0, 10.0, true));
    s->ringColour = o.colour("ring_colour", s->ringColour);
    s->smokeImpulse = float(o.number("smoke_impulse", s->smokeImpulse, 0.0, 1000.0));
    s->smokeRadius = float(o.number("smoke_radius", s->smokeRadius, 0.0, 10.0, true));
    s->smokeColour = o.colour("smoke_colour", s->smokeColour);
    s->look.intensity = 3.0f;
    s->look.additive = true;
    readParticleLook(o, s->look);
    return s;
}

namespace {

// A 32-bit integer hash (lowbias32) as a number in [0, 1).
float unitHash(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return float(x >> 8) * (1.0f / 16777216.0f);
}

} // namespace

BlowAxes blowAxes(glm::vec3 direction) {
    BlowAxes b;
    if (glm::length(direction) > 1e-6f) b.along = glm::normalize(direction);
    const glm::vec3 helper =
        std::abs(b.along.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    b.u = glm::normalize(glm::cross(b.along, helper));
    b.v = glm::cross(b.along, b.u);
    return b;
}

std::vector<SparkLaunch> impactSparks(const ImpactSpec& impact, glm::vec3 point,
                                      glm::vec3 direction, float time, uint32_t hitIndex) {
    std::vector<SparkLaunch> out;
    const BlowAxes blow = blowAxes(direction);
    const glm::vec3 axis = blow.along, u = blow.u, v = blow.v;
    const float cosSpread = std::cos(glm::radians(impact.sparkSpread));
    for (uint32_t i = 0; i < impact.sparks; ++i) {
        const uint32_t seed = hitIndex * 0x9e3779b9U + i * 4u;
        // Uniform over the spherical cap: cos(theta) uniform in [cos(spread), 1].
        const float cosTheta = 1.0f - unitHash(seed) * (1.0f - cosSpread);
        const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
        const float phi = 6.2831853f * unitHash(seed + 1);
        const glm::vec3 d = axis * cosTheta + (u * std::cos(phi) + v * std::sin(phi)) * sinTheta;
        SparkLaunch s;
        s.origin = point;
        s.time = time;
        s.velocity = d * (impact.sparkSpeed * (0.5f + unitHash(seed + 2)));
        s.life = impact.sparkLife * (0.6f + 0.4f * unitHash(seed + 3));
        out.push_back(s);
    }
    return out;
}

glm::vec3 sparkPosition(glm::vec3 origin, glm::vec3 velocity, float gravity, float drag, float t) {
    const glm::vec3 g(0.0f, -gravity, 0.0f);
    const float kt = drag * t;
    // (1 - e^(-kt)) / k and (kt - 1 + e^(-kt)) / k^2, by series where kt is small.
    const float reach =
        kt < 1e-3f ? t * (1.0f - 0.5f * kt + kt * kt / 6.0f) : -std::expm1(-kt) / drag;
    const float fall = kt < 1e-3f ? t * t * (0.5f - kt / 6.0f + kt * kt / 24.0f)
                                  : (kt + std::expm1(-kt)) / (drag * drag);
    return origin + velocity * reach + g * fall;
}

float impactLifetime(const ImpactSpec& impact) {
    return std::max({impact.sparks > 0 ? impact.sparkLife : 0.0f, impact.flashSeconds,
                     impact.ring != RingFacing::None ? impact.ringSeconds : 0.0f});
}

} // namespace mfx::scene
