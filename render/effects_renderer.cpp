#include "render/effects_renderer.h"

#include "sim/scene_simulation.h"

#include <algorithm>

namespace mfx::render {

EffectsRenderer::EffectsRenderer(const gpu::Context& ctx, const sim::SceneSimulation& simulation,
                                 VkSampleCountFlagBits samples)
    : passes_(makeEffectPasses(ctx, simulation, samples)), smokePass_(ctx),
      shown_(simulation.scene().effects.size(), 1),
      fadesAgainstDepth_(
          std::any_of(simulation.scene().effects.begin(), simulation.scene().effects.end(),
                      [](const scene::EffectSpec& e) { return e.kind().fadesAgainstDepth(); })) {
    for (const auto& pass : passes_)
        pass->setCamera(&camera_);
}

void EffectsRenderer::setShown(size_t effect, bool shown) {
    if (effect < shown_.size()) shown_[effect] = shown ? 1 : 0;
}

void EffectsRenderer::advance(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                              uint32_t frame) {
    for (const auto& pass : passes_)
        pass->advance(cmd, simulation, frame);
}

uint32_t EffectsRenderer::drawEffects(VkCommandBuffer cmd, RenderTarget& target,
                                      const sim::SceneSimulation& simulation, float time) {
    if (fadesAgainstDepth_) { // the scene's depth, for the soft effects to read
        endRendering(cmd);
        copyFadeDepth(cmd, target);
        resumeRendering(cmd, target);
    }
    uint32_t draws = 0;
    for (const auto& pass : passes_) {
        pass->setFadeDepth(fadesAgainstDepth_ ? &target.fadeDepth : nullptr);
        draws += pass->draw(cmd, simulation, camera_, time, shown_);
    }
    endRendering(cmd);
    return draws;
}

void EffectsRenderer::drawSmoke(VkCommandBuffer cmd, RenderTarget& target,
                                const sim::SceneSimulation& simulation,
                                const SmokeRelight* relight) {
    smokePass_.draw(cmd, target, simulation, camera_, shown_, smokeLook_, relight);
}

} // namespace mfx::render
