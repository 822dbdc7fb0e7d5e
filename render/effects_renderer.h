// The effects of a frame: the scene's effect passes (render/effect_kinds.cpp) and its smoke,
// drawn into a render target that already holds the picture's depth. The one path by which
// motionfx draws effects: into its own frame (FrameRenderer: the scene's target, straight after
// the character and the stage) and into a host application's (HostFrame, the runtime library:
// a layer of their own over the host's depth, laid over the host's colour).
#pragma once

#include "render/effect_kind_pass.h"
#include "render/render_target.h"
#include "render/scene_camera.h"
#include "render/smoke_pass.h"

#include <memory>
#include <vector>

namespace mfx::render {

class EffectsRenderer {
public:
    // The passes `simulation`'s scene calls for, drawing into targets of `samples` samples. As
    // FrameRenderer, it draws any later simulation of the same scene and character.
    EffectsRenderer(const gpu::Context& ctx, const sim::SceneSimulation& simulation,
                    VkSampleCountFlagBits samples);

    // Whether an effect fades in front of the scene's surfaces (depth_fade): the target's
    // rendering must then be begun resumable, so that drawEffects can copy its depth.
    bool fadesAgainstDepth() const { return fadesAgainstDepth_; }

    // The camera the effects are drawn from (and advance() builds view-dependent geometry for).
    void setCamera(const SceneCamera& camera) { camera_ = camera; }
    const SceneCamera& camera() const { return camera_; }

    // Records the effect passes' work for simulation frame `frame` (after the simulation's
    // recordFrame for it, before any drawing).
    void advance(VkCommandBuffer cmd, const sim::SceneSimulation& simulation, uint32_t frame);

    // Inside the target's open rendering (its depth the picture's; begun resumable when
    // fadesAgainstDepth()): copies the fade depth, records the effect passes' draws at scene
    // time `time` and ends the rendering. Returns the number of draws.
    uint32_t drawEffects(VkCommandBuffer cmd, RenderTarget& target,
                         const sim::SceneSimulation& simulation, float time);
    // After drawEffects: the smoke grids composited over the target's colour (with `relight`, lit
    // as it says).
    void drawSmoke(VkCommandBuffer cmd, RenderTarget& target,
                   const sim::SceneSimulation& simulation, const SmokeRelight* relight = nullptr);

    // How the smoke is marched (render/smoke_pass.h; the defaults unless set).
    void setSmokeLook(const SmokeLook& look) { smokeLook_ = look; }
    const SmokeLook& smokeLook() const { return smokeLook_; }

    // Which of the scene's effects are drawn, by their index in scene.effects (all by default).
    // A smoke grid is drawn while any of its effects is shown.
    void setShown(size_t effect, bool shown);
    bool shown(size_t effect) const { return effect < shown_.size() && shown_[effect] != 0; }

    // The effect pass of type `Pass` (render/effect_kinds.cpp); null when the scene has no effect
    // it draws.
    template <class Pass>
    const Pass* effectPass() const {
        for (const auto& pass : passes_)
            if (const auto* p = dynamic_cast<const Pass*>(pass.get())) return p;
        return nullptr;
    }

private:
    std::vector<std::unique_ptr<EffectKindPass>> passes_; // in draw order
    SmokePass smokePass_;
    SmokeLook smokeLook_;
    SceneCamera camera_;
    std::vector<uint8_t> shown_;
    bool fadesAgainstDepth_ = false;
};

} // namespace mfx::render
