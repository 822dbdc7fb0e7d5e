// The viewer's window picture (motionfx view): the frame's 8-bit output copied into a swapchain
// image, letterboxed, with status lines drawn over it; and the image copied out for a screenshot.
#pragma once

#include "core/gpu/resources.h"
#include "render/render_target.h"

#include <glm/glm.hpp>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

namespace mfx::app {

struct StatusLine {
    std::string text;
    glm::vec4 colour{1.0f};
};

// Records `target`'s output scaled into swapchain image `image` (letterboxed, black around it)
// and then `lines` from the top-left corner and `bottom` (when not empty) at the bottom-left, as
// text on dark boxes. Leaves the image in colour-attachment layout. Returns the picture's height
// on screen in pixels.
float recordWindowPicture(VkCommandBuffer cmd, render::RenderTarget& target, VkImage image,
                          VkImageView view, VkExtent2D extent, const std::vector<StatusLine>& lines,
                          const StatusLine& bottom);

// Records a copy of `image` (colour-attachment layout, left so) into `buffer`, made here for
// `extent` (RGBA8 or BGRA8 texels, as the swapchain's format).
void recordCopyOut(const gpu::Context& ctx, VkCommandBuffer cmd, VkImage image, VkExtent2D extent,
                   gpu::Buffer& buffer);

// The RGBA8 pixels of a copy made by recordCopyOut, blue and red swapped back for BGRA formats.
std::vector<uint8_t> copiedPixels(const gpu::Buffer& buffer, VkExtent2D extent, VkFormat format);

} // namespace mfx::app
