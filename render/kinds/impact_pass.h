// The impact (core/scene/kinds/impact_effect.h): at each of the scene's hits (scene.hits, found by
// fitScene) its sparks, flash and shockwave ring.
//
// The hits are known before the first frame, so every spark of every hit is thrown once, on the
// host, when the pass is made (scene::impactSparks: origin, velocity, life), into one buffer per
// effect. Each new frame, advance() evaluates the sparks of the hits still alive at the frame's
// time on their closed-form flight paths (shaders/render/impact_sparks.comp, impact_flight.glsl):
// a streak from where each was `spark_stretch` seconds ago to where it is now. draw() draws the
// streaks turned to the camera, with the look's colour and size over life, then each live hit's
// flash (a soft glow growing and fading over flash_seconds, over everything in front of it) and
// ring (a band growing to ring_radius over ring_seconds, facing the camera, over everything, or
// lying on the plane across the blow) (shaders/render/impact.*).
#pragma once

#include "core/anim/character.h"
#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/scene/kinds/impact_effect.h"
#include "core/scene/scene.h"
#include "render/effect_geometry.h"
#include "render/effect_kind_pass.h"
#include "shaders/shared/impact.h"

#include <span>
#include <vector>

namespace mfx::render {

class ImpactPass : public EffectKindPass {
public:
    // Registry (render/effect_kind_pass.h): after the trails, light on top of them.
    static constexpr const char* kPassName = "impact";
    static constexpr int kDrawOrder = 50;
    static std::vector<std::string> drawnTypes() { return {scene::ImpactSpec::kType}; }

    // The scene must be fitted (its hits found: the simulation's scene is).
    ImpactPass(const gpu::Context& ctx, const scene::Scene& scene,
               std::span<const anim::Character> cast,
               VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);

    void advance(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                 uint32_t frame) override;
    uint32_t draw(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                  const SceneCamera& camera, float time,
                  std::span<const uint8_t> shown = {}) override;

    // The sparks of effect `effect` (index in scene.effects) as thrown, and, after an advance()
    // has finished executing, their streaks at its frame (read back; empty for another effect).
    std::vector<shared::ImpactSpark> sparks(size_t effect) const;
    std::vector<shared::ImpactStreak> streaks(size_t effect) const;

private:
    struct Effect {
        size_t index = 0; // in scene.effects
        const scene::ImpactSpec* spec = nullptr;
        std::vector<size_t> hits;         // its hits, in scene.hits
        std::vector<uint32_t> firstSpark; // of each of its hits, in `sparks`
        uint32_t sparkCount = 0;
        gpu::Buffer sparks, streaks, style;
        // The sparks advance() evaluated: [first, first + count) (none: count 0).
        uint32_t evaluatedFirst = 0, evaluatedCount = 0;
    };

    const gpu::Context& ctx_;
    scene::Scene scene_; // a copy, with its hits
    std::vector<Effect> effects_;
    // The sparks and the ring on the hit plane are depth tested; the flash and a camera-facing
    // ring are drawn over everything (the bodies that meet at the contact point would hide them),
    // as a fighting game's hit flash is.
    gpu::Program sparksProgram_, draw_, overlay_;
    gpu::Buffer frame_;
    FadeDepthSource fadeDepthSource_;
};

} // namespace mfx::render
