// What the passes of the trajectory effects share (render/kinds/motion_blur_pass.h,
// speed_lines_pass.h, motion_particles_pass.h): the simulation keeps each effect's trajectory
// queue (sim/scene_simulation.h, SceneSimulation::trajectories()), and the pass draws the live
// segments of the queues of its one kind, inside the frame's rendering (after the opaque scene,
// depth test on, no depth write, premultiplied alpha). Every sample's alpha is its attenuation
// along the segment times 1 - age / lifetime (Xu et al., Algorithm 1).
//
// A kind's pass derives from TrailEffectPass, gives it the draw program, and says what each of
// its effects binds and pushes: its look's uniform buffer (made once per effect), the bindings
// past the scene frame and the look, and the width or size and look in shared::EffectDraw.
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "render/effect_geometry.h"
#include "render/effect_kind_pass.h"
#include "shaders/shared/effect_draw.h"
#include "sim/scene_simulation.h"

#include <map>
#include <span>
#include <string>
#include <vector>

namespace mfx::render {

class TrailEffectPass : public EffectKindPass {
public:
    // Draws the live segments of every effect of the pass's type at scene time `now` (with
    // `shown` non-empty, only the effects whose entry is non-zero). Returns the number of draws.
    uint32_t draw(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                  const SceneCamera& camera, float now, std::span<const uint8_t> shown) override;
    // The queues advance with the simulation (SceneSimulation::recordFrame): nothing to do, for a
    // kind that keeps nothing of its own.
    void advance(VkCommandBuffer, const sim::SceneSimulation&, uint32_t) override {}

protected:
    using TrajectoryEffect = sim::SceneSimulation::TrajectoryEffect;

    // A pass drawing the effects of scene type `type` with `program`.
    TrailEffectPass(const gpu::Context& ctx, const char* type, gpu::Program program);

    // The effect's look as program binding 1 (ribbonStyleBuffer or volumeStyleBuffer), made once.
    virtual gpu::Buffer makeStyle(const scene::EffectSpec& spec) const = 0;
    // The bindings past the frame (0) and the style (1) for the draws of `effect`, of
    // `simulation`.
    virtual std::vector<gpu::DescriptorWrite> extraBindings(const sim::SceneSimulation& simulation,
                                                            const TrajectoryEffect& effect) {
        (void)simulation;
        (void)effect;
        return {};
    }
    // The effect's width or size (timing.z) and look in the draw's push constants.
    virtual void setLook(shared::EffectDraw& draw, const TrajectoryEffect& effect) const = 0;
    // What draws the effect's segments: a program and an index buffer with the indices of one
    // segment (each segment's draw offsets them by its first vertex), or no index buffer (each
    // segment's vertices in order). By default the pass's program and the queue's own indices.
    struct DrawSource {
        const gpu::Program* program = nullptr;
        VkBuffer indices = VK_NULL_HANDLE;
        uint32_t indexCount = 0;
    };
    virtual DrawSource drawSource(const TrajectoryEffect& effect);

    // The trajectory effects of the pass's type.
    template <class Fn>
    void forEachEffect(const sim::SceneSimulation& simulation, Fn&& fn) const {
        for (const TrajectoryEffect& effect : simulation.trajectories())
            if (effect.spec->type() == type_) fn(effect);
    }

    const gpu::Context& ctx_;

private:
    std::string type_;
    gpu::Program program_;
    gpu::Buffer frame_;
    std::map<size_t, gpu::Buffer> styles_; // each effect's look, by effect index
};

} // namespace mfx::render
