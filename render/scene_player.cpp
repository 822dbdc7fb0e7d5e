#include "render/scene_player.h"

#include "core/gpu/commands.h"

namespace mfx::render {

ScenePlayer::ScenePlayer(const gpu::Context& ctx, sim::SceneSimulation& simulation, uint32_t width,
                         uint32_t height, VkSampleCountFlagBits samples)
    : ctx_(ctx), simulation_(&simulation), renderer_(ctx, simulation, width, height, samples) {}

sim::SimulationFrameStats ScenePlayer::play(uint32_t frame,
                                            const gpu::PrimitiveCounter* primitives) {
    gpu::submitOneShot(ctx_, [&](VkCommandBuffer cmd) {
        if (primitives) primitives->begin(cmd);
        record(cmd, frame);
        if (primitives) primitives->end(cmd);
    });
    return finish();
}

void ScenePlayer::record(VkCommandBuffer cmd, uint32_t frame) {
    renderer_.record(cmd, *simulation_, frame);
    pending_ = true;
}

sim::SimulationFrameStats ScenePlayer::finish() {
    if (!pending_) return {};
    pending_ = false;
    sim::SimulationFrameStats stats = simulation_->finishFrame();
    for (const gpu::PassTime& p : renderer_.passTimes())
        stats.passes.push_back({"render/" + p.name, 0, p.milliseconds});
    return stats;
}

void ScenePlayer::recordRedraw(VkCommandBuffer cmd, float time) {
    renderer_.recordDraw(cmd, *simulation_, time);
}

} // namespace mfx::render
