// Scenes drawn as `motionfx render` draws them, for tests that look at whole frames: a scene of
// docs/scenes/ loaded, simulated and drawn frame by frame through a FrameRenderer.
#pragma once

#include "core/gpu/commands.h"
#include "core/scene/scene.h"
#include "render/frame_renderer.h"
#include "sim/scene_simulation.h"

#include <memory>
#include <string>

namespace mfx::test {

// docs/scenes/NAME.json.
inline Result<scene::Scene> docScene(const std::string& name) {
    return scene::loadScene(std::string(MFX_SOURCE_DIR) + "/docs/scenes/" + name + ".json");
}

// Plays `frames` frames from frame `first` (as the simulation requires, in order).
inline void playFrames(const gpu::Context& ctx, render::FrameRenderer& renderer,
                       sim::SceneSimulation& simulation, uint32_t first, uint32_t frames) {
    for (uint32_t f = first; f < first + frames; ++f) {
        gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) { renderer.record(cmd, simulation, f); });
        simulation.finishFrame();
    }
}

// A scene, its characters, simulation and renderer, which draw the frames played.
struct DrawnScene {
    std::unique_ptr<scene::Cast> cast; // outlives the simulation and the renderer
    std::unique_ptr<sim::SceneSimulation> simulation;
    std::unique_ptr<render::FrameRenderer> renderer;

    // Plays up to and including frame `last` (default: the scene's last).
    void playTo(const gpu::Context& ctx, uint32_t last = ~0u) {
        const uint32_t end = last < simulation->frameCount() ? last + 1 : simulation->frameCount();
        playFrames(ctx, *renderer, *simulation, played, end - std::min(played, end));
        played = std::max(played, end);
    }
    uint32_t played = 0;
};

// `s` at `width` x `height` (its output size is set to that), nothing played yet.
inline Result<DrawnScene> drawScene(const gpu::Context& ctx, scene::Scene s, uint32_t width,
                                    uint32_t height,
                                    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT) {
    s.output.width = width;
    s.output.height = height;
    Result<scene::Cast> cast = scene::loadCast(s);
    if (!cast) return cast.error();
    DrawnScene drawn;
    drawn.cast = std::make_unique<scene::Cast>(std::move(cast).value());
    auto simulation = sim::SceneSimulation::create(ctx, s, *drawn.cast);
    if (!simulation) return simulation.error();
    drawn.simulation = std::move(simulation).value();
    drawn.renderer =
        std::make_unique<render::FrameRenderer>(ctx, *drawn.simulation, width, height, samples);
    return drawn;
}

} // namespace mfx::test
