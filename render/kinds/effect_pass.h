// The effect passes: what the trajectory queues hold, drawn over the scene (inside the same
// rendering, after the opaque scene pass; depth test on, no depth write, premultiplied alpha):
//   * motion volumes (blur): the swept side walls, lit with their stored normals, with a Fresnel
//     rim and colour over life;
//   * speed-lines: each line piece widened into a camera-facing ribbon (geometry stage), tapering
//     along the segment and with age, with a white-hot core;
//   * motion particles: round soft camera-facing sprites (geometry stage), with colour and size
//     over life.
// Every sample's alpha is its attenuation along the segment times 1 - age / lifetime.
#pragma once

#include <map>

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/scene/kinds/trail_effects.h"
#include "render/effect_geometry.h"
#include "render/effect_kind_pass.h"
#include "render/scene_camera.h"
#include "sim/scene_simulation.h"

#include <span>
#include <string>
#include <vector>

namespace mfx::render {

class EffectPass : public EffectKindPass {
public:
    // Registry (render/effect_kind_pass.h): after the mesh effects; within the pass, blur volumes,
    // then speed-lines, then particles, so the thin effects stay on top.
    static constexpr const char* kPassName = "trajectory";
    static constexpr int kDrawOrder = 40;
    static std::vector<std::string> drawnTypes() {
        return {scene::MotionBlurSpec::kType, scene::SpeedLinesSpec::kType,
                scene::MotionParticlesSpec::kType};
    }

    explicit EffectPass(const gpu::Context& ctx,
                        VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);

    // Draws every drawn effect (speed-lines, blur, particles) of `simulation` at scene time
    // `now`; with `shown` non-empty, only the effects whose entry (by index in scene.effects) is
    // non-zero. Returns the number of draws recorded.
    uint32_t draw(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                  const SceneCamera& camera, float now,
                  std::span<const uint8_t> shown = {}) override;
    // The queues advance with the simulation (SceneSimulation::recordFrame): nothing to do.
    void advance(VkCommandBuffer, const sim::SceneSimulation&, uint32_t) override {}

private:
    const gpu::Context& ctx_;
    gpu::Program volumes_, lines_, particles_;
    gpu::Buffer frame_;
    FadeDepthSource fadeDepthSource_;
    // Each effect's look (ribbon_style.glsl), by effect index.
    std::map<size_t, gpu::Buffer> styles_;
};

} // namespace mfx::render
