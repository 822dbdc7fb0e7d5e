#include "render/smoke_pass.h"

#include "core/gpu/context.h"
#include "shaders/embedded.h"
#include "shaders/shared/smoke_draw.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace mfx::render {

namespace {

constexpr uint32_t kBoxVertices = 36; // six faces, two triangles each (shaders/render/smoke.vert)
constexpr VkFormat kFluidColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kFluidDistanceFormat = VK_FORMAT_R32_SFLOAT;
// Where either march reads the scene's depth and the light's transmittance.
constexpr VkPipelineStageFlags2 kMarchStages =
    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

// The volume's shading for the march: the preset's colour ramp by pigment alpha, its glow and cel
// bands, and the key light.
shared::SmokeStyle smokeStyle(const scene::SmokeShading& shading, const scene::LightSpec& key) {
    shared::SmokeStyle style{};
    using P = scene::SmokePreset;
    if (shading.preset == P::Fire) {
        style.ramp[0] = {0.45f, 0.04f, 0.0f, 0.0f};
        style.ramp[1] = {1.0f, 0.3f, 0.03f, 0.3f};
        style.ramp[2] = {1.0f, 0.7f, 0.2f, 0.65f};
        style.ramp[3] = {1.0f, 0.95f, 0.75f, 1.0f};
    } else if (shading.preset == P::Energy) {
        style.ramp[0] = {0.05f, 0.25f, 1.0f, 0.0f};
        style.ramp[1] = {0.2f, 0.7f, 1.0f, 0.4f};
        style.ramp[2] = {0.6f, 0.95f, 1.0f, 0.75f};
        style.ramp[3] = {1.0f, 1.0f, 1.0f, 1.0f};
    } else {
        for (int i = 0; i < 4; ++i)
            style.ramp[i] = glm::vec4(1.0f, 1.0f, 1.0f, float(i) / 3.0f);
    }
    const float preset = shading.preset == P::Fire     ? MFX_SMOKE_PRESET_FIRE
                         : shading.preset == P::Energy ? MFX_SMOKE_PRESET_ENERGY
                                                       : MFX_SMOKE_PRESET_SMOKE;
    style.params = glm::vec4(shading.glow, float(shading.celBands), key.intensity, preset);
    style.light = glm::vec4(key.colour, shading.anisotropy);
    return style;
}

// An sRGB-encoded value (as the picture shows it) in linear light, the scene target's.
float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
glm::vec3 srgbToLinear(glm::vec3 c) {
    return {srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)};
}

// The cartoon look's style (shaders/render/smoke_cartoon.glsl): band k of n the ramp's colour at
// k / (n - 1), the threshold, billows at `time`, rim and ink.
shared::SmokeStyle cartoonStyle(const scene::CartoonSmoke& cartoon, const scene::LightSpec& key,
                                float time) {
    shared::SmokeStyle style{};
    const std::vector<scene::GradientStop>& ramp =
        cartoon.colours.empty() ? scene::cartoonColours() : cartoon.colours;
    const uint32_t bands = std::clamp(cartoon.bands, 2u, 4u);
    for (uint32_t k = 0; k < bands; ++k)
        style.ramp[k] = glm::vec4(
            srgbToLinear(glm::vec3(scene::colourAt(ramp, float(k) / float(bands - 1)))), 1.0f);
    style.params = glm::vec4(cartoon.rim, float(bands), key.intensity, MFX_SMOKE_PRESET_CARTOON);
    style.light = glm::vec4(key.colour, 0.0f);
    style.surface = glm::vec4(cartoon.threshold, cartoon.billow, cartoon.billowScale,
                              time * cartoon.billowSpeed);
    style.outline = glm::vec4(srgbToLinear(cartoon.outlineColour), cartoon.outlineWidth);
    return style;
}

uint32_t divisorOf(SmokeResolution resolution) {
    return resolution == SmokeResolution::Full ? 1u : 2u;
}

// The march's programs (shaders/render/smoke_march.glsl) for a fluid buffer of 1 / divisor of the
// picture: the fragment march over the box's faces, and the compute march.
gpu::GraphicsProgramDesc fragmentMarchDesc(uint32_t divisor, bool sparse, bool cartoon) {
    gpu::GraphicsProgramDesc march;
    march.name = cartoon ? (sparse ? "smoke_cartoon_sparse" : "smoke_cartoon")
                         : (sparse ? "smoke_sparse" : "smoke");
    march.vertex = shaders::smoke_vert;
    march.fragment =
        cartoon ? (sparse ? shaders::smoke_frag_cartoon_sparse : shaders::smoke_frag_cartoon)
                : (sparse ? shaders::smoke_frag_sparse : shaders::smoke_frag);
    march.pushConstantSize = sizeof(shared::SmokeDraw);
    march.specialization = {divisor};
    march.colorFormats = {kFluidColorFormat, kFluidDistanceFormat};
    march.blend = gpu::BlendMode::Opaque;
    return march;
}

gpu::ComputeProgramDesc computeMarchDesc(uint32_t divisor, bool sparse, bool cartoon) {
    gpu::ComputeProgramDesc march;
    march.name = cartoon ? (sparse ? "smoke_cartoon_march_sparse" : "smoke_cartoon_march")
                         : (sparse ? "smoke_march_sparse" : "smoke_march");
    march.spirv = cartoon ? (sparse ? shaders::smoke_march_comp_cartoon_sparse
                                    : shaders::smoke_march_comp_cartoon)
                          : (sparse ? shaders::smoke_march_comp_sparse : shaders::smoke_march_comp);
    march.pushConstantSize = sizeof(shared::SmokeDraw);
    march.specialization = {divisor};
    return march;
}

} // namespace

SmokePass::SmokePass(const gpu::Context& ctx) : ctx_(ctx) {
    // The pigment box search, for rgba32f pigment and for a solver's fp16 (rgba16f) pigment.
    for (bool half : {false, true}) {
        gpu::ComputeProgramDesc bounds;
        bounds.name = "pigment_bounds";
        bounds.spirv = half ? shaders::pigment_bounds_comp_half : shaders::pigment_bounds_comp;
        bounds.pushConstantSize = sizeof(shared::PigmentBoundsDispatch);
        boundsPrograms_[half ? 1 : 0] = gpu::createComputeProgram(ctx, bounds);
    }
    volumeSampler_ =
        gpu::createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER);
    nearestSampler_ =
        gpu::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    edgeSampler_ = gpu::createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    gpu::ComputeProgramDesc light;
    light.name = "light_transmittance";
    light.spirv = shaders::light_transmittance_comp;
    light.pushConstantSize = sizeof(shared::SmokeDraw);
    light_ = gpu::createComputeProgram(ctx, light);
    // The default's pipelines made up front.
    const uint32_t divisor = divisorOf(SmokeLook{}.resolution);
    marchProgram(programsFor(divisor), divisor, computeMarch(SmokeLook{}), false, false);
}

bool SmokePass::computeMarch(const SmokeLook& look) const {
    return look.march == SmokeMarch::Compute ||
           (look.march == SmokeMarch::Auto && !ctx_.info().isCpu());
}

gpu::Program& SmokePass::marchProgram(Programs& programs, uint32_t divisor, bool compute,
                                      bool sparse, bool cartoon) {
    std::optional<gpu::Program>& slot =
        programs.march[compute ? 1 : 0][sparse ? 1 : 0][cartoon ? 1 : 0];
    if (!slot)
        slot = compute
                   ? gpu::createComputeProgram(ctx_, computeMarchDesc(divisor, sparse, cartoon))
                   : gpu::createGraphicsProgram(ctx_, fragmentMarchDesc(divisor, sparse, cartoon));
    return *slot;
}

gpu::Program& SmokePass::cartoonComposite(Programs& programs, uint32_t divisor) {
    if (!programs.cartoonComposite) {
        gpu::GraphicsProgramDesc composite = fragmentMarchDesc(divisor, false, false);
        composite.name = "smoke_cartoon_composite";
        composite.fragment = shaders::smoke_cartoon_composite_frag;
        composite.colorFormats = {kSceneColorFormat};
        composite.blend = gpu::BlendMode::PremultipliedAlpha;
        programs.cartoonComposite = gpu::createGraphicsProgram(ctx_, composite);
    }
    return *programs.cartoonComposite;
}

SmokePass::Programs& SmokePass::programsFor(uint32_t divisor) {
    auto it = programs_.find(divisor);
    if (it != programs_.end()) return it->second;
    Programs programs;
    gpu::GraphicsProgramDesc composite = fragmentMarchDesc(divisor, false, false);
    composite.name = "smoke_composite";
    composite.fragment = shaders::smoke_composite_frag;
    composite.colorFormats = {kSceneColorFormat};
    composite.blend = gpu::BlendMode::PremultipliedAlpha;
    programs.composite = gpu::createGraphicsProgram(ctx_, composite);
    return programs_.emplace(divisor, std::move(programs)).first->second;
}

void SmokePass::prepareFluidBuffer(const RenderTarget& target, uint32_t divisor) {
    if (fluid_.divisor == divisor && fluid_.targetWidth == target.width &&
        fluid_.targetHeight == target.height)
        return;
    gpu::ImageDesc desc;
    desc.extent = {(target.width + divisor - 1) / divisor, (target.height + divisor - 1) / divisor,
                   1};
    desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                 VK_IMAGE_USAGE_SAMPLED_BIT;
    desc.format = kFluidColorFormat;
    desc.debugName = "smoke fluid buffer colour";
    fluid_.color = gpu::createImage(ctx_, desc);
    desc.format = kFluidDistanceFormat;
    desc.debugName = "smoke fluid buffer distance";
    fluid_.distance = gpu::createImage(ctx_, desc);
    fluid_.divisor = divisor;
    fluid_.targetWidth = target.width;
    fluid_.targetHeight = target.height;
}

void SmokePass::findPigmentBounds(VkCommandBuffer cmd, std::span<const Volume> volumes,
                                  const SmokeLook& look) {
    // Each volume's box emptied, after the previous draw's reads of it.
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, 0,
                       VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const shared::PigmentBounds empty{glm::uvec4(0xffffffffu), glm::uvec4(0u)};
    for (size_t i = 0; i < volumes.size(); ++i)
        vkCmdUpdateBuffer(cmd, bounds_[i].get(), 0, sizeof(empty), &empty);
    // The solver's writes (compute, copies) and the emptied boxes before the search and the march.
    // (A sparse grid's active list is also read as the bounds search's indirect arguments.)
    gpu::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
            VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
            VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
    for (size_t i = 0; i < volumes.size(); ++i) {
        const fluid::GridShape& shape = volumes[i].shape;
        shared::PigmentBoundsDispatch d{};
        d.size = glm::uvec4(shape.cellsX, shape.cellsY, shape.cellsZ, 0u);
        d.threshold = look.pigmentThreshold;
        const fluid::PigmentVolume& pigment = volumes[i].pigment;
        if (pigment.layout == fluid::PigmentLayout::BrickAtlas) {
            gpu::Program& sparseBounds = madeOnce(sparseBounds_, "pigment_bounds_sparse",
                                                  shaders::pigment_bounds_comp_sparse,
                                                  sizeof(shared::PigmentBoundsDispatch));
            sparseBounds.bind(cmd,
                              {gpu::bindBuffer(0, *pigment.atlas), gpu::bindBuffer(1, bounds_[i]),
                               gpu::bindBuffer(2, *pigment.brickTable),
                               gpu::bindBuffer(3, *pigment.activeList)});
            sparseBounds.push(cmd, d);
            vkCmdDispatchIndirect(cmd, pigment.activeList->get(), 0);
            continue;
        }
        gpu::Program& bounds = boundsFor(*pigment.image);
        bounds.bind(cmd, {gpu::bindImage(0, *pigment.image, VK_IMAGE_LAYOUT_GENERAL),
                          gpu::bindBuffer(1, bounds_[i])});
        bounds.push(cmd, d);
        vkCmdDispatch(cmd, gpu::groupCount(shape.cellsX, MFX_PIGMENT_BOUNDS_GROUP_X),
                      gpu::groupCount(shape.cellsY, MFX_PIGMENT_BOUNDS_GROUP_Y),
                      gpu::groupCount(shape.cellsZ, MFX_PIGMENT_BOUNDS_GROUP_Z));
    }
    // The boxes → the light's march and the proxy's vertices.
    gpu::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

gpu::Program& SmokePass::madeOnce(std::optional<gpu::Program>& slot, const char* name,
                                  std::span<const uint32_t> spirv, uint32_t pushConstantSize) {
    if (!slot) {
        gpu::ComputeProgramDesc desc;
        desc.name = name;
        desc.spirv = spirv;
        desc.pushConstantSize = pushConstantSize;
        slot = gpu::createComputeProgram(ctx_, desc);
    }
    return *slot;
}

void SmokePass::marchLight(VkCommandBuffer cmd, size_t i, const Volume& volume,
                           const shared::SmokeDraw& draw, uint32_t maxCells) {
    const fluid::GridShape& shape = volume.shape;
    // Room for the pigment's box (found on the GPU) at a texel a cell, at most maxCells a side (a
    // box wider than that shares a texel between cells); the march covers the box's cells only. At
    // half the resolution a dense block's lit faces took their light from 5 cm inside, visibly
    // darker.
    maxCells = std::max(maxCells, 1u);
    const VkExtent3D extent{std::min(shape.cellsX, maxCells), std::min(shape.cellsY, maxCells),
                            std::min(shape.cellsZ, maxCells)};
    if (lights_.size() <= i) lights_.resize(i + 1);
    gpu::Image& image = lights_[i];
    if (!image.image || image.extent.width != extent.width ||
        image.extent.height != extent.height || image.extent.depth != extent.depth) {
        gpu::ImageDesc desc;
        desc.extent = extent;
        desc.format = VK_FORMAT_R32_SFLOAT;
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        desc.is3D = true;
        desc.debugName = "smoke light transmittance";
        image = gpu::createImage(ctx_, desc);
    }
    // The previous draw's fetches → this march's stores (what the draw fetches is rewritten: the
    // box's texels and the layer past it).
    gpu::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_GENERAL, kMarchStages, 0,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    const fluid::PigmentVolume& pigment = volume.pigment;
    gpu::Program* program = &light_;
    std::vector<gpu::DescriptorWrite> writes = {gpu::bindBuffer(2, bounds_[i]),
                                                gpu::bindImage(5, image, VK_IMAGE_LAYOUT_GENERAL)};
    if (pigment.layout == fluid::PigmentLayout::BrickAtlas) {
        program = &madeOnce(sparseLight_, "light_transmittance_sparse",
                            shaders::light_transmittance_comp_sparse, sizeof(shared::SmokeDraw));
        writes.push_back(gpu::bindBuffer(0, *pigment.atlas));
        writes.push_back(gpu::bindBuffer(4, *pigment.brickTable));
    } else {
        writes.push_back(
            gpu::bindImage(0, *pigment.image, VK_IMAGE_LAYOUT_GENERAL, volumeSampler_.get()));
    }
    program->bind(cmd, writes);
    program->push(cmd, draw);
    vkCmdDispatch(cmd, gpu::groupCount(extent.width, 4), gpu::groupCount(extent.height, 4),
                  gpu::groupCount(extent.depth, 4));
    gpu::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kMarchStages,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

uint32_t SmokePass::draw(VkCommandBuffer cmd, RenderTarget& target,
                         const sim::SceneSimulation& simulation, const SceneCamera& camera,
                         std::span<const uint8_t> shown, const SmokeLook& look,
                         const SmokeRelight* relight) {
    std::vector<Volume> volumes;
    for (const sim::SceneSimulation::SmokeGrid& grid : simulation.smokeGrids()) {
        bool visible = shown.empty();
        for (size_t e : grid.effects) {
            const size_t index = simulation.effectIndex(simulation.trajectories()[e]);
            visible = visible || (index < shown.size() && shown[index] != 0);
        }
        if (!visible) continue;
        const scene::SmokeSpec* smoke =
            grid.effects.empty() ? nullptr : simulation.trajectories()[grid.effects[0]].smoke;
        volumes.push_back({grid.grid.pigmentVolume(), grid.grid.options().grid, grid.grid.origin(),
                           smoke ? smoke->shading : scene::SmokeShading{},
                           simulation.frameTime(simulation.recordedFrame())});
    }
    if (volumes.empty()) return 0;
    scene::LightSpec key =
        simulation.scene().lights.empty() ? scene::LightSpec{} : simulation.scene().lights.front();
    if (relight) {
        key = relight->key;
        for (Volume& v : volumes)
            v.shading.glow *= relight->glowScale;
    }
    draw(cmd, target, volumes, camera, key, look);
    return uint32_t(volumes.size());
}

void SmokePass::draw(VkCommandBuffer cmd, RenderTarget& target, std::span<const Volume> volumes,
                     const SceneCamera& camera, const scene::LightSpec& key,
                     const SmokeLook& look) {
    if (volumes.empty()) return;
    const uint32_t divisor = divisorOf(look.resolution);
    const bool compute = computeMarch(look);
    Programs& programs = programsFor(divisor);
    prepareFluidBuffer(target, divisor);
    while (bounds_.size() < volumes.size())
        bounds_.push_back(
            gpu::createBuffer(ctx_, sizeof(shared::PigmentBounds),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                              gpu::MemoryUsage::DeviceLocal, "smoke pigment bounds"));
    while (styles_.size() < volumes.size())
        styles_.push_back(gpu::createBuffer(ctx_, sizeof(shared::SmokeStyle),
                                            VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                            gpu::MemoryUsage::Upload, "smoke style"));
    for (size_t i = 0; i < volumes.size(); ++i) {
        const scene::SmokeShading& shading = volumes[i].shading;
        const shared::SmokeStyle style = shading.preset == scene::SmokePreset::Cartoon
                                             ? cartoonStyle(shading.cartoon, key, volumes[i].time)
                                             : smokeStyle(shading, key);
        std::memcpy(styles_[i].mapped, &style, sizeof style);
    }
    findPigmentBounds(cmd, volumes, look);
    // The scene's depth as a texture.
    gpu::imageBarrier(cmd, target.depth, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT |
                          VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      kMarchStages, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);

    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    const VkSampler nearest = nearestSampler_.get();
    for (size_t i = 0; i < volumes.size(); ++i) {
        const Volume& v = volumes[i];
        const fluid::GridShape& shape = v.shape;
        shared::SmokeDraw d{};
        d.inverseViewProjection = glm::inverse(camera.viewProjection);
        d.gridOrigin = glm::vec4(v.origin, shape.cellSize);
        d.gridSize = glm::vec4(float(shape.cellsX), float(shape.cellsY), float(shape.cellsZ),
                               look.stepsPerCell);
        d.eye = glm::vec4(camera.eye, look.fadeDistance);
        d.light = glm::vec4(-glm::normalize(key.direction), look.densityScale);
        marchLight(cmd, i, v, d, look.maxLightCells);

        march(cmd, target, i, v, d, programs, divisor, compute);

        // The composite over the picture.
        for (gpu::Image* image : {&fluid_.color, &fluid_.distance})
            gpu::imageBarrier(cmd, *image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                              compute ? VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT
                                      : VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                              compute ? VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT
                                      : VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                              VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                              VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        beginCompositing(cmd, target);
        std::vector<gpu::DescriptorWrite> writes = {
            gpu::bindImage(0, fluid_.color, read, nearest),
            gpu::bindImage(1, fluid_.distance, read, nearest), gpu::bindBuffer(2, bounds_[i]),
            gpu::bindImage(3, target.depth, read, nearest)};
        gpu::Program* composite = &programs.composite;
        if (cartoon(v)) {
            composite = &cartoonComposite(programs, divisor);
            writes.push_back(gpu::bindBuffer(4, styles_[i]));
        }
        composite->bind(cmd, writes);
        composite->push(cmd, d);
        vkCmdDraw(cmd, kBoxVertices, 1, 0, 0);
        vkCmdEndRendering(cmd);
    }
}

void SmokePass::march(VkCommandBuffer cmd, RenderTarget& target, size_t i, const Volume& volume,
                      const shared::SmokeDraw& draw, Programs& programs, uint32_t divisor,
                      bool compute) {
    const bool sparse = volume.pigment.layout == fluid::PigmentLayout::BrickAtlas;
    gpu::Program& program = marchProgram(programs, divisor, compute, sparse, cartoon(volume));
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    std::vector<gpu::DescriptorWrite> writes = {
        gpu::bindImage(1, target.depth, read, nearestSampler_.get()),
        gpu::bindBuffer(2, bounds_[i]), gpu::bindBuffer(3, styles_[i]),
        gpu::bindImage(5, lights_[i], VK_IMAGE_LAYOUT_GENERAL, edgeSampler_.get())};
    if (sparse) {
        writes.push_back(gpu::bindBuffer(0, *volume.pigment.atlas));
        writes.push_back(gpu::bindBuffer(4, *volume.pigment.brickTable));
    } else {
        writes.push_back(gpu::bindImage(0, *volume.pigment.image, VK_IMAGE_LAYOUT_GENERAL,
                                        volumeSampler_.get()));
    }
    const VkExtent3D fluidSize = fluid_.color.extent;
    // The fluid buffer written after the previous composite's reads: by the compute march every
    // texel, by the fragment march the texels its box covers, into the cleared buffer.
    for (gpu::Image* image : {&fluid_.color, &fluid_.distance})
        gpu::imageBarrier(cmd, *image,
                          compute ? VK_IMAGE_LAYOUT_GENERAL
                                  : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                          VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, 0,
                          compute ? VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT
                                  : VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                          compute ? VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT
                                  : VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    if (compute) {
        writes.push_back(gpu::bindImage(6, fluid_.color, VK_IMAGE_LAYOUT_GENERAL));
        writes.push_back(gpu::bindImage(7, fluid_.distance, VK_IMAGE_LAYOUT_GENERAL));
        program.bind(cmd, writes);
        program.push(cmd, draw);
        vkCmdDispatch(cmd, gpu::groupCount(fluidSize.width, 8),
                      gpu::groupCount(fluidSize.height, 8), 1);
        return;
    }
    VkRenderingAttachmentInfo attachments[2];
    for (int a = 0; a < 2; ++a) {
        attachments[a] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        attachments[a].imageView = (a == 0 ? fluid_.color : fluid_.distance).view.get();
        attachments[a].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        attachments[a].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        attachments[a].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    }
    attachments[1].clearValue.color.float32[0] = float(MFX_SMOKE_NO_DISTANCE);
    // The cartoon look's margin where no ray was marched: far outside its surface.
    if (cartoon(volume))
        attachments[0].clearValue.color.float32[0] = -volume.shading.cartoon.threshold;
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {fluidSize.width, fluidSize.height}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 2;
    rendering.pColorAttachments = attachments;
    vkCmdBeginRendering(cmd, &rendering);
    // The picture's viewport scaled by 1 / divisor (flipped, +y up, as the target's), so a fluid
    // texel's centre is the centre of its block of pixels.
    const float w = float(target.width) / float(divisor);
    const float h = float(target.height) / float(divisor);
    const VkViewport viewport{0.0f, h, w, -h, 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    const VkRect2D scissor{{0, 0}, {fluidSize.width, fluidSize.height}};
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    program.bind(cmd, writes);
    program.push(cmd, draw);
    vkCmdDraw(cmd, kBoxVertices, 1, 0, 0);
    vkCmdEndRendering(cmd);
}

} // namespace mfx::render
