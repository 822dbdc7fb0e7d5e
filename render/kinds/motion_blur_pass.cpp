#include "render/kinds/motion_blur_pass.h"

namespace mfx::render {

MotionBlurPass::MotionBlurPass(const gpu::Context& ctx, VkSampleCountFlagBits samples)
    : TrailEffectPass(ctx, scene::MotionBlurSpec::kType,
                      trajectoryDrawProgram(ctx, "effect_volume", TrajectoryShape::Triangles,
                                            samples, false)) {}

gpu::Buffer MotionBlurPass::makeStyle(const scene::EffectSpec& spec) const {
    return volumeStyleBuffer(ctx_, spec.as<scene::MotionBlurSpec>()->look);
}

void MotionBlurPass::setLook(shared::EffectDraw& draw, const TrajectoryEffect& effect) const {
    setVolumeLook(draw, effect.spec->as<scene::MotionBlurSpec>()->look, false);
}

} // namespace mfx::render
