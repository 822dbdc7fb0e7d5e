// One frame of a scene, drawn: the character's skinning and shadow, the scene pass, the effects
// (render/effects_renderer.h: the effect passes and the smoke composite) in linear HDR colour, then
// the bloom and the tone map into the 8-bit output, recorded into one command buffer after the
// simulation's own work for that frame, each pass bracketed by a GPU timestamp. `motionfx render`,
// `bench frame` and `view` and the golden-image tests all draw through it.
#pragma once

#include "core/gpu/timer.h"
#include "render/bloom_pass.h"
#include "render/character_pass.h"
#include "render/effects_renderer.h"
#include "render/render_target.h"
#include "render/tone_map_pass.h"
#include "sim/scene_simulation.h"

#include <memory>
#include <string>
#include <vector>

namespace mfx::render {

// The passes a frame records, in order, by the names their timings carry ("skin" includes the
// effect passes' advance: the afterimage smears', swept volumes' and silhouette shells' skinning,
// history and geometry; "effects" the effect passes' draws). "outline" is left out without a
// toon outline, "bloom" without bloom.
inline constexpr const char* kFramePassNames[] = {"skin",    "shadow", "scene", "outline",
                                                  "effects", "smoke",  "bloom", "tone_map"};

class FrameRenderer {
public:
    // A target of `width` × `height` with up to `wantedSamples` samples per pixel (fewer where the
    // device allows fewer), for the scene and characters of `simulation`. The characters must
    // outlive the renderer; the simulation need not: the renderer draws any later simulation of
    // the same scene and characters (a restarted view).
    FrameRenderer(const gpu::Context& ctx, const sim::SceneSimulation& simulation, uint32_t width,
                  uint32_t height, VkSampleCountFlagBits wantedSamples = VK_SAMPLE_COUNT_4_BIT);

    // Records the simulation's frame `frame` (its trajectories and smoke steps) and then the
    // drawing of it. The previous recording must have finished executing.
    void record(VkCommandBuffer cmd, sim::SceneSimulation& simulation, uint32_t frame);
    // Records only the drawing of what the simulation holds now, at scene time `time` (a paused
    // view redraws the same frame this way). Afterimage smears, swept volumes and silhouette shells
    // are drawn as last built: their history advances with record() only, so a paused frame does
    // not change.
    void recordDraw(VkCommandBuffer cmd, const sim::SceneSimulation& simulation, float time);

    // Which of the scene's effects are drawn, by their index in scene.effects (all by default).
    // A smoke grid is drawn while any of its effects is shown.
    void setShown(size_t effect, bool shown) { effects_.setShown(effect, shown); }
    void setSmokeLook(const SmokeLook& look) { effects_.setSmokeLook(look); }
    bool shown(size_t effect) const { return effects_.shown(effect); }

    // After the recording has finished executing: the GPU milliseconds of each drawing pass
    // (kFramePassNames; empty without timestamp support) and the number of effect draws.
    std::vector<gpu::PassTime> passTimes() const { return timer_.results(); }
    uint32_t effectDraws() const { return draws_; }

    // The scene target (linear HDR colour and depth, after the bloom) and the 8-bit sRGB output.
    RenderTarget& sceneTarget() { return target_; }
    RenderTarget& output() { return output_; }
    // The frame's effect pass of type `Pass` (render/effect_kinds.cpp); null when the scene has
    // no effect it draws.
    template <class Pass>
    const Pass* effectPass() const {
        return effects_.effectPass<Pass>();
    }
    const SceneCamera& camera() const { return camera_; }
    // Draws from `camera` from now on instead of the scene's camera (a viewer's orbit camera).
    // Either is shaken by the scene's hits (scene::cameraShake) at the time drawn.
    void setCamera(const scene::CameraSpec& camera);

private:
    // recordDraw; with `frame`, the effect passes also advance to that simulation frame.
    void recordFrame(VkCommandBuffer cmd, const sim::SceneSimulation& simulation, float time,
                     const uint32_t* frame);

    const gpu::Context& ctx_;
    RenderTarget target_;
    RenderTarget output_;
    CharacterPass scenePass_;
    EffectsRenderer effects_;
    BloomPass bloomPass_;
    ToneMapPass toneMapPass_;
    scene::PostSpec post_;
    SceneCamera camera_;
    scene::CameraSpec cameraSpec_; // the scene's or setCamera's, before any shake
    gpu::GpuTimer timer_;
    uint32_t draws_ = 0;
};

// The background colour every frame is cleared to (linear).
inline constexpr glm::vec4 kClearColour{0.02f, 0.02f, 0.03f, 1.0f};

} // namespace mfx::render
