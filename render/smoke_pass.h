// The smoke pass: every smoke grid of a simulation ray-marched through its pigment volume and
// composited over the rendered picture (shaders/smoke.frag), after the scene and effect passes:
// the march stops at the scene's depth, and smoke behind a surface fades out over `fadeDistance`
// (DESIGN.md "Formulas"), so it meets the floor and the character softly.
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "fluid/scene_simulation.h"
#include "render/render_target.h"
#include "render/scene_camera.h"

#include <map>
#include <span>
#include <utility>

namespace mfx::render {

struct SmokeLook {
    float densityScale = 8.0f; // optical density per unit of pigment alpha, per world unit
    float fadeDistance = 0.1f; // b, world units
    float stepsPerCell = 1.0f;
};

class SmokePass {
public:
    explicit SmokePass(const gpu::Context& ctx);

    // Records the composite of every grid of `simulation` into `target`'s single-sampled colour
    // (outside any rendering; after the scene's rendering has ended, so its depth is resolved).
    // With `shown` non-empty, a grid is drawn only while one of its effects' entries (by index in
    // scene.effects) is non-zero. Returns the number of grids drawn.
    uint32_t draw(VkCommandBuffer cmd, RenderTarget& target,
                  const fluid::SceneSimulation& simulation, const SceneCamera& camera,
                  std::span<const uint8_t> shown = {}, const SmokeLook& look = {});

    // One pigment volume (rgba32f, GENERAL layout) of `shape` whose low corner is at `origin`.
    struct Volume {
        const gpu::Image* pigment = nullptr;
        fluid::GridShape shape;
        glm::vec3 origin{0.0f};
    };
    void draw(VkCommandBuffer cmd, RenderTarget& target, std::span<const Volume> volumes,
              const SceneCamera& camera, const scene::LightSpec& key, const SmokeLook& look = {});

private:
    const gpu::Context& ctx_;
    gpu::Program program_;
    gpu::UniqueSampler volumeSampler_, depthSampler_;
    std::map<std::pair<VkImageView, VkImageView>, VkDescriptorSet> sets_;
};

} // namespace mfx::render
