#include "render/frame_renderer.h"

#include "core/scene/scene_hits.h"

namespace mfx::render {

FrameRenderer::FrameRenderer(const gpu::Context& ctx, const sim::SceneSimulation& simulation,
                             uint32_t width, uint32_t height, VkSampleCountFlagBits wantedSamples)
    : ctx_(ctx),
      target_(createRenderTarget(ctx, width, height, supportedSamples(ctx, wantedSamples))),
      output_(createOutputTarget(ctx, width, height)),
      scenePass_(ctx, simulation.cast(), simulation.scene(), target_.samples),
      effects_(ctx, simulation, target_.samples), bloomPass_(ctx), toneMapPass_(ctx),
      post_(simulation.scene().post),
      camera_(makeCamera(simulation.scene().camera, float(width) / float(height))),
      cameraSpec_(simulation.scene().camera), timer_(ctx, uint32_t(std::size(kFramePassNames))) {
    effects_.setCamera(camera_);
}

void FrameRenderer::setCamera(const scene::CameraSpec& camera) {
    cameraSpec_ = camera;
    camera_ = makeCamera(camera, float(target_.width) / float(target_.height));
    effects_.setCamera(camera_);
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
    // The hits' shake, at the time drawn.
    if (const glm::vec3 shake = scene::cameraShake(simulation.scene(), time);
        shake != glm::vec3(0.0f) || camera_.eye != cameraSpec_.position) {
        scene::CameraSpec shaken = cameraSpec_;
        shaken.position += shake;
        shaken.target += shake;
        camera_ = makeCamera(shaken, float(target_.width) / float(target_.height));
        effects_.setCamera(camera_);
    }
    timer_.reset(cmd);
    {
        gpu::ScopedPass pass(timer_, cmd, "skin");
        scenePass_.skin(cmd, simulation.framePoses(), simulation.placements());
        if (frame) effects_.advance(cmd, simulation, *frame);
    }
    {
        gpu::ScopedPass pass(timer_, cmd, "shadow");
        scenePass_.shadow(cmd);
    }
    {
        gpu::ScopedPass pass(timer_, cmd, "scene");
        beginRendering(cmd, target_, kClearColour, effects_.fadesAgainstDepth());
        scenePass_.draw(cmd, camera_);
    }
    if (scenePass_.hasOutline()) {
        gpu::ScopedPass pass(timer_, cmd, "outline");
        scenePass_.drawOutline(cmd, target_.width, target_.height);
    }
    {
        gpu::ScopedPass pass(timer_, cmd, "effects");
        draws_ = effects_.drawEffects(cmd, target_, simulation, time);
    }
    {
        gpu::ScopedPass pass(timer_, cmd, "smoke");
        effects_.drawSmoke(cmd, target_, simulation);
    }
    if (post_.bloom > 0.0f) {
        gpu::ScopedPass pass(timer_, cmd, "bloom");
        bloomPass_.record(cmd, target_.color, post_.bloom);
    }
    gpu::ScopedPass pass(timer_, cmd, "tone_map");
    toneMapPass_.record(cmd, target_.color, output_, post_);
}

} // namespace mfx::render
