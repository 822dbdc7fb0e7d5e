// What the passes of the mesh effects share (the afterimage smear, the swept volume and the
// silhouette shell: each keeps its own history of the bound mesh, render/effect_geometry.h): their
// effects (one MeshEffect-derived entry per scene effect of their kind), the skinning, the frame
// history, the scene-frame buffer, finding an effect by its index in scene.effects, reading back
// what a build wrote, and drawing it.
//
// As an EffectKindPass, each pass's advance() skins the bound vertices, moves the history on and
// builds the geometry; draw() draws what was last built (a paused frame draws the same).
#pragma once

#include "core/anim/character.h"
#include "core/anim/skin_vertices.h"
#include "core/gpu/resources.h"
#include "render/effect_geometry.h"
#include "render/effect_kind_pass.h"
#include "shaders/shared/trajectory.h"
#include "sim/scene_simulation.h"

#include <algorithm>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace mfx::render {

template <class EffectT>
class MeshEffectPass : public EffectKindPass {
public:
    using Effect = EffectT;
    using Kind = decltype(Effect::kind);
    // The registry's (render/effect_kind_pass.h): the one type of the pass's effects.
    static std::vector<std::string> drawnTypes() { return {Kind::kType}; }

    bool empty() const { return effects_.empty(); }

    // Once a new frame (not the frame recorded last): beginFrame(), then each effect's bound
    // vertices skinned in the frame's pose and its recordEffect(); the built geometry is then
    // made visible to the draws.
    void advance(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                 uint32_t frame) final {
        if (effects_.empty()) return;
        const FrameHistory::Step step = history_.step(simulation.serial(), frame);
        if (step == FrameHistory::Step::Same) return; // the same frame again: the history stays
        const bool reset = step == FrameHistory::Step::Restart;
        beginFrame(simulation, reset);
        for (Effect& effect : effects_) {
            const size_t c = scene::effectCharacter(simulation.scene(),
                                                    simulation.scene().effects[effect.index]);
            effect.skin(cmd, skinning_, cast_[c], simulation.framePose(c), simulation.placement(c));
            recordEffect(cmd, simulation, frame, effect, reset);
        }
        computeToDrawBarrier(cmd);
    }

    // The triangles the last advance() built, with draw_ (nothing before the first advance). The
    // afterimage, which draws lines and arcs as well, draws its own.
    uint32_t draw(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                  const SceneCamera& camera, float /*time*/,
                  std::span<const uint8_t> shown = {}) override {
        if (effects_.empty() || !history_.recorded()) return 0;
        return drawBuiltEffects(cmd, effects_, simulation.scene(), camera, shown, frame_, draw_);
    }

protected:
    MeshEffectPass(const gpu::Context& ctx, std::span<const anim::Character> cast)
        : ctx_(ctx), cast_(cast), skinning_(ctx) {}

    // The scene's effects of the pass's kind whose selection of their character's vertices
    // (scene::effectSource) is not empty: their index in scene.effects, settings and selection.
    // Each pass's constructor makes its effects from these (the simulation refuses a scene with
    // an empty selection first), and a scene without the kind makes none and pays for nothing.
    struct Selected {
        size_t index;
        const Kind* kind;
        trajectory::Source source;
    };
    std::vector<Selected> selectedEffects(const scene::Scene& scene) const {
        std::vector<Selected> out;
        for (size_t i = 0; i < scene.effects.size(); ++i) {
            const Kind* kind = scene.effects[i].template as<Kind>();
            if (!kind) continue;
            const size_t c = scene::effectCharacter(scene, scene.effects[i]);
            if (c >= cast_.size()) continue;
            Result<trajectory::Source> selected = scene::effectSource(cast_[c], scene.effects[i]);
            if (selected && !selected.value().vertices.empty())
                out.push_back({i, kind, std::move(selected).value()});
        }
        return out;
    }

    // What a new frame does before its effects (nothing, unless the pass says otherwise).
    virtual void beginFrame(const sim::SceneSimulation& /*simulation*/, bool /*reset*/) {}
    // One effect's work of frame `frame`, its bound vertices skinned; `reset`: its history starts
    // again (the first frame, a jump, a new simulation).
    virtual void recordEffect(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                              uint32_t frame, Effect& effect, bool reset) = 0;

    const Effect* find(size_t effect) const { return findEffect(effects_, effect); }
    // The counters effect `effect`'s last build wrote (after the recording finished executing);
    // zero for an effect the pass does not have.
    template <class Counters>
    Counters builtCounters(size_t effect) const {
        Counters c{};
        if (const Effect* e = find(effect)) std::memcpy(&c, e->counters.mapped, sizeof c);
        return c;
    }
    // The first `count` vertices effect `effect`'s last build wrote into its output. Reads back;
    // waits.
    std::vector<shared::TrajectoryVertex> builtVertices(size_t effect, size_t count) const {
        const Effect* e = find(effect);
        if (!e) return {};
        auto vertices = gpu::readBufferAs<shared::TrajectoryVertex>(ctx_, e->output);
        vertices.resize(std::min(vertices.size(), count));
        return vertices;
    }

    const gpu::Context& ctx_;
    std::span<const anim::Character> cast_;
    anim::SkinVertices skinning_;
    gpu::Program draw_; // the built triangles' pipeline
    gpu::Buffer frame_;
    std::vector<Effect> effects_;
    FrameHistory history_;
};

} // namespace mfx::render
