#include "render/bloom_pass.h"

#include "render/render_target.h"
#include "shaders/embedded.h"
#include "shaders/shared/post.h"

#include <algorithm>

namespace mfx::render {

namespace {

gpu::Program program(const gpu::Context& ctx, const char* name, std::span<const uint32_t> spirv) {
    gpu::ComputeProgramDesc desc;
    desc.name = name;
    desc.spirv = spirv;
    desc.pushConstantSize = sizeof(shared::BloomStep);
    return gpu::createComputeProgram(ctx, desc);
}

VkExtent2D half(VkExtent2D e) {
    return {std::max(1u, (e.width + 1) / 2), std::max(1u, (e.height + 1) / 2)};
}

// Compute writes before the reads (as textures) of the next step.
void writesToReads(VkCommandBuffer cmd) {
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

} // namespace

BloomPass::BloomPass(const gpu::Context& ctx)
    : ctx_(ctx), downsample_(program(ctx, "bloom_downsample", shaders::bloom_downsample_comp)),
      upsample_(program(ctx, "bloom_upsample", shaders::bloom_upsample_comp)),
      composite_(program(ctx, "bloom_composite", shaders::bloom_composite_comp)),
      sampler_(gpu::createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE)) {}

uint32_t BloomPass::levelCount(uint32_t width, uint32_t height) {
    uint32_t levels = 0;
    VkExtent2D e{width, height};
    while (levels < kMaxLevels && std::min(e.width, e.height) >= 8) {
        e = half(e);
        ++levels;
    }
    return std::max(levels, 1u);
}

void BloomPass::prepare(uint32_t width, uint32_t height) {
    if (width == width_ && height == height_) return;
    down_.clear();
    up_.clear();
    VkExtent2D e{width, height};
    const uint32_t levels = levelCount(width, height);
    for (uint32_t i = 0; i < levels; ++i) {
        e = half(e);
        gpu::ImageDesc desc;
        desc.extent = {e.width, e.height, 1};
        desc.format = kSceneColorFormat;
        desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        desc.debugName = "bloom level";
        down_.push_back(gpu::createImage(ctx_, desc));
        desc.debugName = "bloom sum";
        up_.push_back(i + 1 < levels ? gpu::createImage(ctx_, desc) : gpu::Image{});
    }
    width_ = width;
    height_ = height;
}

void BloomPass::record(VkCommandBuffer cmd, gpu::Image& picture, float strength) {
    prepare(picture.extent.width, picture.extent.height);
    const uint32_t levels = uint32_t(down_.size());
    const VkImageLayout general = VK_IMAGE_LAYOUT_GENERAL;
    const VkSampler sampler = sampler_.get();
    // The picture after the colour writes (and resolves) of its rendering, and every level of the
    // pyramid after the last frame's reads, in GENERAL: written as storage, read as textures.
    gpu::imageBarrier(cmd, picture, general, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    for (uint32_t i = 0; i < levels; ++i)
        for (gpu::Image* image : {&down_[i], &up_[i]})
            if (*image)
                gpu::imageBarrier(cmd, *image, general, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                  VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                  VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

    auto dispatch = [&](const gpu::Program& program, const gpu::Image& written,
                        const gpu::Image& read, shared::BloomStep s) {
        s.size = glm::uvec4(written.extent.width, written.extent.height, read.extent.width,
                            read.extent.height);
        program.push(cmd, s);
        vkCmdDispatch(cmd, gpu::groupCount(written.extent.width, MFX_BLOOM_GROUP_X),
                      gpu::groupCount(written.extent.height, MFX_BLOOM_GROUP_Y), 1);
        writesToReads(cmd);
    };
    // Down: the picture into level 0, each level into the next.
    for (uint32_t i = 0; i < levels; ++i) {
        const gpu::Image& source = i == 0 ? picture : down_[i - 1];
        downsample_.bind(cmd, {gpu::bindImage(0, source, general, sampler),
                               gpu::bindImage(1, down_[i], general)});
        dispatch(downsample_, down_[i], source, {});
    }
    // Up: each level plus the sum of the coarser ones (the coarsest level is its own sum).
    auto sumOf = [&](uint32_t i) -> const gpu::Image& {
        return i + 1 == levels ? down_[i] : up_[i];
    };
    for (uint32_t i = levels - 1; i-- > 0;) {
        upsample_.bind(cmd, {gpu::bindImage(0, sumOf(i + 1), general, sampler),
                             gpu::bindImage(1, down_[i], general, sampler),
                             gpu::bindImage(2, up_[i], general)});
        dispatch(upsample_, up_[i], sumOf(i + 1), {});
    }
    // The picture mixed with the whole sum over the number of levels.
    composite_.bind(
        cmd, {gpu::bindImage(0, sumOf(0), general, sampler), gpu::bindImage(1, picture, general)});
    shared::BloomStep s{};
    s.weights = glm::vec4(strength, 1.0f / float(levels), 0.0f, 0.0f);
    s.size = glm::uvec4(picture.extent.width, picture.extent.height, sumOf(0).extent.width,
                        sumOf(0).extent.height);
    composite_.push(cmd, s);
    vkCmdDispatch(cmd, gpu::groupCount(picture.extent.width, MFX_BLOOM_GROUP_X),
                  gpu::groupCount(picture.extent.height, MFX_BLOOM_GROUP_Y), 1);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                       VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
}

} // namespace mfx::render
