#include "render/render_target.h"

#include "core/gpu/context.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <stdexcept>

namespace mfx::render {

VkSampleCountFlagBits supportedSamples(const gpu::Context& ctx, VkSampleCountFlagBits wanted) {
    const VkSampleCountFlags both =
        ctx.limits().framebufferColorSampleCounts & ctx.limits().framebufferDepthSampleCounts;
    for (uint32_t s = wanted; s > 1; s >>= 1)
        if (both & s) return VkSampleCountFlagBits(s);
    return VK_SAMPLE_COUNT_1_BIT;
}

namespace {

// A width x height attachment image of `format`.
gpu::Image attachment(const gpu::Context& ctx, uint32_t width, uint32_t height, VkFormat format,
                      VkImageUsageFlags usage, VkSampleCountFlagBits samples, const char* name) {
    gpu::ImageDesc desc;
    desc.extent = {width, height, 1};
    desc.format = format;
    desc.usage = usage;
    desc.samples = samples;
    desc.debugName = name;
    return gpu::createImage(ctx, desc);
}

} // namespace

RenderTarget createRenderTarget(const gpu::Context& ctx, uint32_t width, uint32_t height,
                                VkSampleCountFlagBits samples) {
    RenderTarget target;
    target.width = width;
    target.height = height;
    target.samples = samples;
    if (samples != VK_SAMPLE_COUNT_1_BIT) {
        target.msaaColor =
            attachment(ctx, width, height, kSceneColorFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                       samples, "render target colour (MSAA)");
        target.msaaDepth = attachment(ctx, width, height, kDepthFormat,
                                      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, samples,
                                      "render target depth (MSAA)");
    }
    // The resolved (or only) images, read back and sampled by the passes after the scene; the
    // bloom writes the colour in place, and tests fill it.
    const VkImageUsageFlags readable = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    target.color = attachment(ctx, width, height, kSceneColorFormat,
                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_DST_BIT | readable,
                              VK_SAMPLE_COUNT_1_BIT, "render target colour");
    target.depth = attachment(ctx, width, height, kDepthFormat,
                              VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | readable,
                              VK_SAMPLE_COUNT_1_BIT, "render target depth");
    target.fadeDepth = attachment(ctx, width, height, kDepthFormat,
                                  VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                  VK_SAMPLE_COUNT_1_BIT, "render target fade depth");
    return target;
}

RenderTarget createOutputTarget(const gpu::Context& ctx, uint32_t width, uint32_t height) {
    RenderTarget target;
    target.width = width;
    target.height = height;
    target.color = attachment(ctx, width, height, kOutputColorFormat,
                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                              VK_SAMPLE_COUNT_1_BIT, "output colour");
    return target;
}

namespace {

// Begins rendering into the target's attachments: colour cleared to `clearColor` or loaded, depth
// cleared to 1 (`clearDepth`) or loaded; with MSAA resolved at the end, the multisampled images
// kept (stored) when `keep`.
void startRendering(VkCommandBuffer cmd, RenderTarget& target, const glm::vec4* clearColor,
                    bool clearDepth, bool keep) {
    const bool msaa = target.samples != VK_SAMPLE_COUNT_1_BIT;
    auto colorBarrier = [&](gpu::Image& image) {
        gpu::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                          VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                          VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
                              VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
    };
    auto depthBarrier = [&](gpu::Image& image) {
        gpu::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                          VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                          VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                              VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT |
                              VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
    };
    colorBarrier(target.color);
    depthBarrier(target.depth);
    if (msaa) {
        colorBarrier(target.msaaColor);
        depthBarrier(target.msaaDepth);
    }

    const VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_LOAD, clear = VK_ATTACHMENT_LOAD_OP_CLEAR;
    const VkAttachmentStoreOp store =
        msaa && !keep ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingAttachmentInfo colorAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    colorAttachment.imageView = (msaa ? target.msaaColor : target.color).view.get();
    colorAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colorAttachment.loadOp = clearColor ? clear : load;
    colorAttachment.storeOp = store;
    if (clearColor)
        std::memcpy(colorAttachment.clearValue.color.float32, clearColor, sizeof(float) * 4);
    VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depthAttachment.imageView = (msaa ? target.msaaDepth : target.depth).view.get();
    depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depthAttachment.loadOp = clearDepth ? clear : load;
    depthAttachment.storeOp = store;
    depthAttachment.clearValue.depthStencil = {1.0f, 0};
    if (msaa) {
        colorAttachment.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
        colorAttachment.resolveImageView = target.color.view.get();
        colorAttachment.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        depthAttachment.resolveMode = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;
        depthAttachment.resolveImageView = target.depth.view.get();
        depthAttachment.resolveImageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    }

    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {target.width, target.height}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &colorAttachment;
    rendering.pDepthAttachment = &depthAttachment;
    vkCmdBeginRendering(cmd, &rendering);
    setWholeViewport(cmd, target);
}

} // namespace

void beginRendering(VkCommandBuffer cmd, RenderTarget& target, const glm::vec4& clearColor,
                    bool resumable) {
    startRendering(cmd, target, &clearColor, true, resumable);
}

void beginRenderingOverDepth(VkCommandBuffer cmd, RenderTarget& target, const glm::vec4& clearColor,
                             bool resumable) {
    startRendering(cmd, target, &clearColor, false, resumable);
}

void resumeRendering(VkCommandBuffer cmd, RenderTarget& target) {
    startRendering(cmd, target, nullptr, false, false);
}

void copyFadeDepth(VkCommandBuffer cmd, RenderTarget& target) {
    gpu::imageBarrier(cmd, target.depth, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT |
                          VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    gpu::imageBarrier(cmd, target.fadeDepth, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageCopy region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1};
    region.dstSubresource = region.srcSubresource;
    region.extent = {target.width, target.height, 1};
    vkCmdCopyImage(cmd, target.depth.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   target.fadeDepth.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    gpu::imageBarrier(cmd, target.fadeDepth, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_READ_BIT);
}

void setWholeViewport(VkCommandBuffer cmd, const RenderTarget& target) {
    // Flipped viewport: +y up in clip space, as in OpenGL and GLM's projections.
    const VkViewport viewport{
        0.0f, float(target.height), float(target.width), -float(target.height), 0.0f, 1.0f};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    const VkRect2D scissor{{0, 0}, {target.width, target.height}};
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void beginColourRendering(VkCommandBuffer cmd, RenderTarget& target, VkAttachmentLoadOp load) {
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = target.color.view.get();
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = load;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {target.width, target.height}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &color;
    vkCmdBeginRendering(cmd, &rendering);
    setWholeViewport(cmd, target);
}

void beginCompositing(VkCommandBuffer cmd, RenderTarget& target) {
    gpu::imageBarrier(
        cmd, target.color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
        VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    beginColourRendering(cmd, target, VK_ATTACHMENT_LOAD_OP_LOAD);
}

void endRendering(VkCommandBuffer cmd) {
    vkCmdEndRendering(cmd);
}

uint8_t encodeSrgb8(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f); // NaN stays NaN: refused below
    if (!(c >= 0.0f)) return 0;
    const float encoded = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return uint8_t(std::lround(encoded * 255.0f));
}

std::vector<float> readLinearColor(const gpu::Context& ctx, RenderTarget& target) {
    if (target.color.format != kSceneColorFormat)
        throw std::logic_error("readLinearColor: the target is not a linear HDR scene target");
    const std::vector<std::byte> bytes = gpu::readImage(ctx, target.color);
    std::vector<uint16_t> halves(bytes.size() / sizeof(uint16_t));
    std::memcpy(halves.data(), bytes.data(), halves.size() * sizeof(uint16_t));
    std::vector<float> rgba(halves.size());
    for (size_t i = 0; i < halves.size(); ++i)
        rgba[i] = glm::unpackHalf1x16(halves[i]);
    return rgba;
}

std::vector<uint8_t> readColor(const gpu::Context& ctx, RenderTarget& target) {
    if (target.color.format == kSceneColorFormat) {
        const std::vector<float> linear = readLinearColor(ctx, target);
        std::vector<uint8_t> rgba(linear.size());
        for (size_t i = 0; i < linear.size(); ++i)
            rgba[i] = i % 4 == 3 ? (linear[i] >= 0.0f
                                        ? uint8_t(std::lround(std::min(linear[i], 1.0f) * 255.0f))
                                        : uint8_t(0))
                                 : encodeSrgb8(linear[i]);
        return rgba;
    }
    const std::vector<std::byte> bytes = gpu::readImage(ctx, target.color);
    std::vector<uint8_t> rgba(bytes.size());
    std::memcpy(rgba.data(), bytes.data(), bytes.size());
    return rgba;
}

std::vector<float> readDepth(const gpu::Context& ctx, RenderTarget& target) {
    const std::vector<std::byte> bytes = gpu::readImage(ctx, target.depth);
    std::vector<float> depth(bytes.size() / sizeof(float));
    std::memcpy(depth.data(), bytes.data(), depth.size() * sizeof(float));
    return depth;
}

} // namespace mfx::render
