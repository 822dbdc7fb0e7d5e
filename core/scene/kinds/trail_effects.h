// The effects drawn from a trajectory queue (Xu et al., section 4): speed-lines (motion lines,
// Sec. 4.2), blur volumes (motion volumes, Sec. 4.4) and motion particles (Sec. 4.3). Each frame
// the queue gets one segment per vertex the effect binds; the pass draws its live segments
// (render/kinds/effect_pass.h).
#pragma once

#include "core/scene/effect_spec.h"

namespace mfx::scene {

namespace detail {
class Object;
}

// The trail keys every trajectory effect (and smoke) has, with `extra` keys of its own after
// them; reading them into `t` over its kind's defaults.
std::vector<std::string> trailKeys(std::initializer_list<const char*> extra = {});
void readTrail(const detail::Object& o, TrailSpec& t);

// A kind with a trail: the simulation keeps a trajectory queue for it.
template <class Kind>
struct TrailEffect : EffectKind<Kind> {
    TrailEffect() = default;
    // A trail of `shape` over every stride-th vertex in one colour.
    TrailEffect(trajectory::Kind shape, uint32_t stride, glm::vec4 colour) {
        trail.shape = shape;
        trail.stride = stride;
        trail.colour = colour;
        trail.useMeshColour = false;
    }
    TrailSpec trail;
    const TrailSpec* queue() const override { return &trail; }
    uint32_t* strideValue() override { return &trail.stride; }
};

struct SpeedLinesSpec : TrailEffect<SpeedLinesSpec> {
    static constexpr const char* kType = "speed_lines";
    SpeedLinesSpec() : TrailEffect(trajectory::Kind::Lines, 6, {1.0f, 0.85f, 0.3f, 1.0f}) {}
    float width = 0.012f; // ribbon width (world units)

    static std::vector<std::string> keys() { return trailKeys({"width"}); }
    static std::unique_ptr<EffectKindSpec> parse(const detail::Object& o);
    StrideTarget strideTarget() const override { return StrideTarget::Lines; }
    std::vector<std::pair<const char*, float*>> lengths() override { return {{"width", &width}}; }
};

struct MotionBlurSpec : TrailEffect<MotionBlurSpec> {
    static constexpr const char* kType = "motion_blur";
    MotionBlurSpec() { // its stride is read but unused: volumes keep every vertex
        trail.shape = trajectory::Kind::Volumes;
        trail.lifetime = 6;
        trail.alphaStart = 0.55f;
    }
    static std::vector<std::string> keys() { return trailKeys(); }
    static std::unique_ptr<EffectKindSpec> parse(const detail::Object& o);
};

struct MotionParticlesSpec : TrailEffect<MotionParticlesSpec> {
    static constexpr const char* kType = "motion_particles";
    MotionParticlesSpec() : TrailEffect(trajectory::Kind::Particles, 3, {0.6f, 0.9f, 1.0f, 1.0f}) {}
    float size = 0.02f; // particle size (world units)

    static std::vector<std::string> keys() { return trailKeys({"size"}); }
    static std::unique_ptr<EffectKindSpec> parse(const detail::Object& o);
    StrideTarget strideTarget() const override { return StrideTarget::Particles; }
    std::vector<std::pair<const char*, float*>> lengths() override { return {{"size", &size}}; }
};

} // namespace mfx::scene
