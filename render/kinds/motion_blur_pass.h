// Motion volumes (blur; Xu et al., Sec. 4.4): the side walls the bound triangles sweep between two
// frames, from the effect's trajectory queue, lit with their stored normals, with a Fresnel rim and
// colour over life (shaders/render/effect_volume.*; render/trail_effect_pass.h).
#pragma once

#include "core/scene/kinds/trail_effects.h"
#include "render/trail_effect_pass.h"

namespace mfx::render {

class MotionBlurPass : public TrailEffectPass {
public:
    // Registry (render/effect_kind_pass.h): after the mesh effects, and first of the trajectory
    // effects, so the thin speed-lines and particles stay on top of the blur.
    static constexpr const char* kPassName = "motion blur";
    static constexpr int kDrawOrder = 40;
    static std::vector<std::string> drawnTypes() { return {scene::MotionBlurSpec::kType}; }

    explicit MotionBlurPass(const gpu::Context& ctx,
                            VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);

private:
    gpu::Buffer makeStyle(const scene::EffectSpec& spec) const override;
    void setLook(shared::EffectDraw& draw, const TrajectoryEffect& effect) const override;
};

} // namespace mfx::render
