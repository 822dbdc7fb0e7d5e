#include "render/smoke_pass.h"

#include "core/gpu/context.h"
#include "shaders/embedded.h"
#include "shaders/shared/smoke_draw.h"

#include <cstring>

namespace mfx::render {

namespace {
constexpr uint32_t kMaxSets = 32;
}

SmokePass::SmokePass(const gpu::Context& ctx) : ctx_(ctx) {
    gpu::GraphicsProgramDesc desc;
    desc.name = "smoke";
    desc.vertex = shaders::smoke_vert;
    desc.fragment = shaders::smoke_frag;
    desc.bindings = {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
                     {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT}};
    desc.pushConstantSize = sizeof(shared::SmokeDraw);
    desc.colorFormats = {kColorFormat};
    desc.blend = gpu::BlendMode::PremultipliedAlpha;
    desc.maxSets = kMaxSets;
    program_ = gpu::createGraphicsProgram(ctx, desc);
    volumeSampler_ =
        gpu::createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER);
    depthSampler_ =
        gpu::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
}

uint32_t SmokePass::draw(VkCommandBuffer cmd, RenderTarget& target,
                         const fluid::SceneSimulation& simulation, const SceneCamera& camera,
                         std::span<const uint8_t> shown, const SmokeLook& look) {
    std::vector<Volume> volumes;
    for (const fluid::SceneSimulation::SmokeGrid& grid : simulation.smokeGrids()) {
        bool visible = shown.empty();
        for (size_t e : grid.effects) {
            const size_t index = simulation.effectIndex(simulation.trajectories()[e]);
            visible = visible || (index < shown.size() && shown[index] != 0);
        }
        if (!visible) continue;
        volumes.push_back({&grid.solver->pigmentImage(), grid.solver->options().grid, grid.origin});
    }
    if (volumes.empty()) return 0;
    const scene::LightSpec key =
        simulation.scene().lights.empty() ? scene::LightSpec{} : simulation.scene().lights.front();
    draw(cmd, target, volumes, camera, key, look);
    return uint32_t(volumes.size());
}

void SmokePass::draw(VkCommandBuffer cmd, RenderTarget& target, std::span<const Volume> volumes,
                     const SceneCamera& camera, const scene::LightSpec& key,
                     const SmokeLook& look) {
    if (volumes.empty()) return;
    // The solver's writes (compute, copies) before the samples; the scene's depth as a texture.
    gpu::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
        VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    gpu::imageBarrier(cmd, target.depth, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT |
                          VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    beginCompositing(cmd, target);

    for (const Volume& v : volumes) {
        const gpu::Image& volume = *v.pigment;
        const auto key2 = std::make_pair(volume.view.get(), target.depth.view.get());
        auto it = sets_.find(key2);
        if (it == sets_.end()) {
            if (sets_.size() == kMaxSets) {
                program_.resetSets(ctx_);
                sets_.clear();
            }
            it = sets_
                     .emplace(key2,
                              program_.createSet(
                                  ctx_, {gpu::bindImage(0, volume, VK_IMAGE_LAYOUT_GENERAL,
                                                        volumeSampler_.get()),
                                         gpu::bindImage(1, target.depth,
                                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                                        depthSampler_.get())}))
                     .first;
        }
        const fluid::GridShape& shape = v.shape;
        shared::SmokeDraw d{};
        d.inverseViewProjection = glm::inverse(camera.viewProjection);
        d.gridOrigin = glm::vec4(v.origin, shape.cellSize);
        d.gridSize = glm::vec4(float(shape.cellsX), float(shape.cellsY), float(shape.cellsZ),
                               look.stepsPerCell);
        d.eye = glm::vec4(camera.eye, look.fadeDistance);
        d.light = glm::vec4(-glm::normalize(key.direction), look.densityScale);
        program_.bind(cmd, it->second);
        program_.push(cmd, d);
        vkCmdDraw(cmd, 3, 1, 0, 0);
    }
    vkCmdEndRendering(cmd);
}

} // namespace mfx::render
