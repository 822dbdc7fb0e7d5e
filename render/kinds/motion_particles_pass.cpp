#include "render/kinds/motion_particles_pass.h"

namespace mfx::render {

MotionParticlesPass::MotionParticlesPass(const gpu::Context& ctx, VkSampleCountFlagBits samples)
    : TrailEffectPass(
          ctx, scene::MotionParticlesSpec::kType,
          trajectoryDrawProgram(ctx, "effect_particles", TrajectoryShape::Sprites, samples, false)),
      fadeDepthSource_(ctx) {}

gpu::Buffer MotionParticlesPass::makeStyle(const scene::EffectSpec& spec) const {
    return ribbonStyleBuffer(ctx_, spec.as<scene::MotionParticlesSpec>()->look);
}

std::vector<gpu::DescriptorWrite> MotionParticlesPass::extraBindings(const sim::SceneSimulation&,
                                                                     const TrajectoryEffect&) {
    return {fadeDepthSource_.binding(fadeDepth_)};
}

void MotionParticlesPass::setLook(shared::EffectDraw& draw, const TrajectoryEffect& effect) const {
    const auto& particles = *effect.spec->as<scene::MotionParticlesSpec>();
    draw.timing.z = particles.size;
    setRibbonLook(draw, particles.look);
}

} // namespace mfx::render
