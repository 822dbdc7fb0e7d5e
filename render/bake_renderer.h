// The effects of a scene drawn alone, for a flipbook (`motionfx bake`, render/flipbook.h): into a
// layer cleared to transparent black, as a host's frame draws them (render/host_frame.h), so its
// colour is premultiplied linear light and its alpha the effects' coverage. The character is left
// out, or kept as a holdout: drawn into the layer's depth alone (its colour cleared away again),
// so that it hides what is behind it and adds nothing of its own. The stage is always left out.
// No bloom and no tone map: the bake applies the scene's tone curve to the layer itself. The smoke
// is marched at full resolution (one ray a pixel).
#pragma once

#include "render/character_pass.h"
#include "render/effects_renderer.h"
#include "render/render_target.h"
#include "render/scene_camera.h"

#include <glm/glm.hpp>
#include <optional>

namespace mfx::render {

// `camera` showing only the part `rect` (x0, y0, x1, y1 in its normalised device coordinates,
// +y up) of its picture, stretched over the whole target: the projection followed by a scale and
// shift in clip space. A rect larger than [-1, 1] shows more than the camera does.
SceneCamera cropCamera(const SceneCamera& camera, const glm::vec4& rect);

class BakeRenderer {
public:
    // A layer of `width` x `height` with up to `samples` samples a pixel, for `simulation`'s scene.
    BakeRenderer(const gpu::Context& ctx, const sim::SceneSimulation& simulation, uint32_t width,
                 uint32_t height, bool holdout,
                 VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT);

    void setCamera(const SceneCamera& camera) { camera_ = camera; }
    const SceneCamera& camera() const { return camera_; }
    // Which of the scene's effects are drawn, by index (all by default).
    void setShown(size_t effect, bool shown) { effects_.setShown(effect, shown); }

    // Records the simulation's frame `frame` and the drawing of its effects into the layer. The
    // previous recording must have finished executing, and the simulation's frame been finished.
    void record(VkCommandBuffer cmd, sim::SceneSimulation& simulation, uint32_t frame);

    // Records the smoke alone drawn again into the layer, cleared first, lit as `relight` says
    // (after record() of the frame, whose submission has finished).
    void recordSmoke(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                     const SmokeRelight& relight);

    // The layer: colour (kSceneColorFormat, premultiplied linear) and depth.
    RenderTarget& layer() { return layer_; }

private:
    // Begins the layer's rendering (cleared) and draws the holdout's depth.
    void beginLayer(VkCommandBuffer cmd, bool resumable);

    RenderTarget layer_;
    EffectsRenderer effects_;
    std::optional<CharacterPass> holdout_;
    SceneCamera camera_;
};

} // namespace mfx::render
