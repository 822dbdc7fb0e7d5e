#include "render/frame_renderer.h"

#include <algorithm>

namespace mfx::render {

namespace {

// Whether an effect of `scene` fades in front of the scene's surfaces: then the frame copies the
// depth between the scene and the effects.
bool fadesAgainstDepth(const scene::Scene& scene) {
    return std::any_of(scene.effects.begin(), scene.effects.end(),
                       [](const scene::EffectSpec& e) { return e.kind().fadesAgainstDepth(); });
}

} // namespace

FrameRenderer::FrameRenderer(const gpu::Context& ctx, const sim::SceneSimulation& simulation,
                             uint32_t width, uint32_t height, VkSampleCountFlagBits wantedSamples)
    : ctx_(ctx),
      target_(createRenderTarget(ctx, width, height, supportedSamples(ctx, wantedSamples))),
      output_(createOutputTarget(ctx, width, height)),
      scenePass_(ctx, simulation.character(), simulation.scene(), target_.samples),
      effectPasses_(makeEffectPasses(ctx, simulation, target_.samples)), smokePass_(ctx),
      bloomPass_(ctx), toneMapPass_(ctx), post_(simulation.scene().post),
      camera_(makeCamera(simulation.scene().camera, float(width) / float(height))),
      timer_(ctx, uint32_t(std::size(kFramePassNames))),
      shown_(simulation.scene().effects.size(), 1),
      fadesAgainstDepth_(fadesAgainstDepth(simulation.scene())) {
    for (const auto& effects : effectPasses_) {
        effects->setFadeDepth(fadesAgainstDepth_ ? &target_.fadeDepth : nullptr);
        effects->setCamera(&camera_);
    }
}

void FrameRenderer::setCamera(const scene::CameraSpec& camera) {
    camera_ = makeCamera(camera, float(target_.width) / float(target_.height));
}

void FrameRenderer::setShown(size_t effect, bool shown) {
    if (effect < shown_.size()) shown_[effect] = shown ? 1 : 0;
}

void FrameRenderer::record(VkCommandBuffer cmd, sim::SceneSimulation& simulation, uint32_t frame) {
    simulation.recordFrame(cmd, frame);
    recordFrame(cmd, simulation, simulation.frameTime(frame), &frame);
}

void FrameRenderer::recordDraw(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                               float time) {
    recordFrame(cmd, simulation, time, nullptr);
}

void FrameRenderer::recordFrame(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                                float time, const uint32_t* frame) {
    timer_.reset(cmd);
    {
        gpu::ScopedPass pass(timer_, cmd, "skin");
        scenePass_.skin(cmd, simulation.framePose(), simulation.placement());
        if (frame)
            for (const auto& effects : effectPasses_)
                effects->advance(cmd, simulation, *frame);
    }
    {
        gpu::ScopedPass pass(timer_, cmd, "shadow");
        scenePass_.shadow(cmd);
    }
    {
        gpu::ScopedPass pass(timer_, cmd, "scene");
        beginRendering(cmd, target_, kClearColour, fadesAgainstDepth_);
        scenePass_.draw(cmd, camera_);
    }
    if (scenePass_.hasOutline()) {
        gpu::ScopedPass pass(timer_, cmd, "outline");
        scenePass_.drawOutline(cmd, target_.width, target_.height);
    }
    {
        gpu::ScopedPass pass(timer_, cmd, "effects");
        if (fadesAgainstDepth_) { // the scene's depth, for the soft effects to read
            endRendering(cmd);
            copyFadeDepth(cmd, target_);
            resumeRendering(cmd, target_);
        }
        draws_ = 0;
        for (const auto& effects : effectPasses_)
            draws_ += effects->draw(cmd, simulation, camera_, time, shown_);
        endRendering(cmd);
    }
    {
        gpu::ScopedPass pass(timer_, cmd, "smoke");
        smokePass_.draw(cmd, target_, simulation, camera_, shown_);
    }
    if (post_.bloom > 0.0f) {
        gpu::ScopedPass pass(timer_, cmd, "bloom");
        bloomPass_.record(cmd, target_.color, post_.bloom);
    }
    gpu::ScopedPass pass(timer_, cmd, "tone_map");
    toneMapPass_.record(cmd, target_.color, output_, post_);
}

} // namespace mfx::render
