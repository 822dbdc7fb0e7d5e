#include "render/bake_renderer.h"

#include "sim/scene_simulation.h"

namespace mfx::render {

SceneCamera cropCamera(const SceneCamera& camera, const glm::vec4& rect) {
    const glm::vec2 centre{0.5f * (rect.x + rect.z), 0.5f * (rect.y + rect.w)};
    const glm::vec2 scale{2.0f / (rect.z - rect.x), 2.0f / (rect.w - rect.y)};
    // x / w -> s (x / w - c): clip x' = s x - s c w, the row (s, 0, 0, -s c); likewise y.
    glm::mat4 m(1.0f);
    m[0][0] = scale.x;
    m[1][1] = scale.y;
    m[3][0] = -scale.x * centre.x;
    m[3][1] = -scale.y * centre.y;
    SceneCamera out = camera;
    out.projection = m * camera.projection;
    out.viewProjection = out.projection * out.view;
    return out;
}

BakeRenderer::BakeRenderer(const gpu::Context& ctx, const sim::SceneSimulation& simulation,
                           uint32_t width, uint32_t height, bool holdout,
                           VkSampleCountFlagBits samples)
    : layer_(createRenderTarget(ctx, width, height, supportedSamples(ctx, samples))),
      effects_(ctx, simulation, layer_.samples),
      camera_(makeCamera(simulation.scene().camera, float(width) / float(height))) {
    if (holdout) holdout_.emplace(ctx, simulation.cast(), simulation.scene(), layer_.samples);
    // One ray a pixel: a cell is small, and what it holds is all there is of the effect.
    SmokeLook look;
    look.resolution = SmokeResolution::Full;
    effects_.setSmokeLook(look);
}

void BakeRenderer::record(VkCommandBuffer cmd, sim::SceneSimulation& simulation, uint32_t frame) {
    simulation.recordFrame(cmd, frame);
    effects_.setCamera(camera_);
    effects_.advance(cmd, simulation, frame);
    if (holdout_) holdout_->skin(cmd, simulation.framePoses(), simulation.placements());
    beginLayer(cmd, effects_.fadesAgainstDepth());
    effects_.drawEffects(cmd, layer_, simulation, simulation.frameTime(frame));
    effects_.drawSmoke(cmd, layer_, simulation);
}

void BakeRenderer::recordSmoke(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                               const SmokeRelight& relight) {
    beginLayer(cmd, false);
    endRendering(cmd);
    effects_.drawSmoke(cmd, layer_, simulation, &relight);
}

void BakeRenderer::beginLayer(VkCommandBuffer cmd, bool resumable) {
    beginRendering(cmd, layer_, glm::vec4(0.0f), resumable);
    if (holdout_) {
        holdout_->draw(cmd, camera_, false);
        // The character's colour cleared away again, its depth kept.
        VkClearAttachment clear{};
        clear.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
        clear.colorAttachment = 0;
        clear.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
        VkClearRect rect{};
        rect.rect = {{0, 0}, {layer_.width, layer_.height}};
        rect.layerCount = 1;
        vkCmdClearAttachments(cmd, 1, &clear, 1, &rect);
    }
}

} // namespace mfx::render
