// Motion particles (Xu et al., Sec. 4.3): every sample of the effect's trajectory queue as a round,
// soft, camera-facing sprite (the geometry stage), with colour and size over life
// (shaders/render/effect_particles.*; render/trail_effect_pass.h).
#pragma once

#include "core/scene/kinds/trail_effects.h"
#include "render/trail_effect_pass.h"

namespace mfx::render {

class MotionParticlesPass : public TrailEffectPass {
public:
    // Registry (render/effect_kind_pass.h): last of the trajectory effects, on top of the blur
    // and the speed-lines.
    static constexpr const char* kPassName = "motion particles";
    static constexpr int kDrawOrder = 42;
    static std::vector<std::string> drawnTypes() { return {scene::MotionParticlesSpec::kType}; }

    explicit MotionParticlesPass(const gpu::Context& ctx,
                                 VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);

private:
    gpu::Buffer makeStyle(const scene::EffectSpec& spec) const override;
    std::vector<gpu::DescriptorWrite> extraBindings(const sim::SceneSimulation& simulation,
                                                    const TrajectoryEffect& effect) override;
    void setLook(shared::EffectDraw& draw, const TrajectoryEffect& effect) const override;

    FadeDepthSource fadeDepthSource_;
};

} // namespace mfx::render
