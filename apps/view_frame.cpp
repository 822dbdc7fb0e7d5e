#include "apps/view_frame.h"

#include "core/gpu/commands.h"
#include "render/text_overlay.h"

#include <algorithm>

namespace mfx::app {

float recordWindowPicture(VkCommandBuffer cmd, render::RenderTarget& target, VkImage image,
                          VkImageView view, VkExtent2D extent, const std::vector<StatusLine>& lines,
                          const StatusLine& bottom) {
    gpu::transitionImage(cmd, target.color, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    gpu::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT);
    // The picture scaled to the window, letterboxed to keep its shape.
    const float scale = std::min(float(extent.width) / float(target.width),
                                 float(extent.height) / float(target.height));
    const int32_t w = std::max(1, int32_t(float(target.width) * scale));
    const int32_t h = std::max(1, int32_t(float(target.height) * scale));
    const int32_t x0 = (int32_t(extent.width) - w) / 2, y0 = (int32_t(extent.height) - h) / 2;
    VkClearColorValue black{{0.0f, 0.0f, 0.0f, 1.0f}};
    VkImageSubresourceRange whole{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &whole);
    gpu::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                      VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(target.width), int32_t(target.height), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[0] = {x0, y0, 0};
    blit.dstOffsets[1] = {x0 + w, y0 + h, 1};
    vkCmdBlitImage(cmd, target.color.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    gpu::imageBarrier(
        cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    // The status lines.
    VkRenderingAttachmentInfo colour{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    colour.imageView = view;
    colour.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, extent};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &colour;
    vkCmdBeginRendering(cmd, &rendering);
    const uint32_t textScale = extent.height >= 400 ? 2 : 1;
    const glm::vec4 shade(0.0f, 0.0f, 0.0f, 1.0f);
    const int margin = int(4 * textScale), lineHeight = int(10 * textScale);
    for (size_t i = 0; i < lines.size(); ++i)
        render::drawText(cmd, lines[i].text, {margin, margin + int(i) * lineHeight}, textScale,
                         lines[i].colour, shade, extent);
    if (!bottom.text.empty())
        render::drawText(cmd, bottom.text, {margin, int(extent.height) - margin - lineHeight},
                         textScale, bottom.colour, shade, extent);
    vkCmdEndRendering(cmd);
    return float(h);
}

void recordCopyOut(const gpu::Context& ctx, VkCommandBuffer cmd, VkImage image, VkExtent2D extent,
                   gpu::Buffer& buffer) {
    const VkDeviceSize bytes = VkDeviceSize(extent.width) * extent.height * 4;
    buffer = gpu::createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               gpu::MemoryUsage::Readback, "view screenshot");
    gpu::imageBarrier(
        cmd, image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
        VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.get(), 1,
                           &copy);
    gpu::imageBarrier(
        cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
        VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
}

std::vector<uint8_t> copiedPixels(const gpu::Buffer& buffer, VkExtent2D extent, VkFormat format) {
    const auto* mapped = static_cast<const uint8_t*>(buffer.mapped);
    std::vector<uint8_t> rgba(mapped, mapped + size_t(extent.width) * extent.height * 4);
    if (format == VK_FORMAT_B8G8R8A8_SRGB || format == VK_FORMAT_B8G8R8A8_UNORM)
        for (size_t p = 0; p < rgba.size(); p += 4)
            std::swap(rgba[p], rgba[p + 2]);
    return rgba;
}

} // namespace mfx::app
