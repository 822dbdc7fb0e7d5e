// GPU memory resources: buffers, 2D and 3D images, samplers, and the helpers that move data
// between them and the CPU. Each resource owns its own VkDeviceMemory (the project allocates a
// few dozen resources, far below maxMemoryAllocationCount).
#pragma once

#include "core/gpu/handle.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>
#include <vulkan/vulkan.h>

namespace mfx::gpu {

class Context;

// Where a resource's memory lives.
enum class MemoryUsage {
    DeviceLocal, // GPU-only; mapped anyway when the device-local type is also host-visible
    Upload,      // host-visible, written by the CPU, read by the GPU
    Readback,    // host-visible and preferably cached, written by the GPU, read by the CPU
};

struct Buffer {
    UniqueBuffer buffer;
    UniqueMemory memory;
    VkDeviceSize size = 0;
    void* mapped = nullptr; // persistent mapping when the memory is host-visible

    VkBuffer get() const { return buffer.get(); }
    explicit operator bool() const { return static_cast<bool>(buffer); }
};

Buffer createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                    MemoryUsage memory, const char* debugName = nullptr);

// Copies `bytes` into `buffer` at `offset`: directly when mapped, else through a staging buffer
// and a one-shot transfer (which waits).
void uploadBuffer(const Context& ctx, const Buffer& buffer, std::span<const std::byte> bytes,
                  VkDeviceSize offset = 0);

// The whole buffer's contents; waits for the GPU (one-shot copy when not mapped).
std::vector<std::byte> readBuffer(const Context& ctx, const Buffer& buffer);

template <typename T>
void uploadBuffer(const Context& ctx, const Buffer& buffer, std::span<const T> values,
                  VkDeviceSize offset = 0) {
    uploadBuffer(ctx, buffer, std::as_bytes(values), offset);
}

template <typename T>
std::vector<T> readBufferAs(const Context& ctx, const Buffer& buffer) {
    const std::vector<std::byte> bytes = readBuffer(ctx, buffer);
    std::vector<T> values(bytes.size() / sizeof(T));
    std::copy(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(values.size() * sizeof(T)),
              reinterpret_cast<std::byte*>(values.data()));
    return values;
}

struct ImageDesc {
    VkExtent3D extent{1, 1, 1}; // depth > 1 makes a 3D image
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    VkImageUsageFlags usage = 0;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    bool is3D = false; // a 3D image even when depth is 1
    const char* debugName = nullptr;
};

struct Image {
    UniqueImage image;
    UniqueMemory memory;
    UniqueImageView view;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent3D extent{};
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    // The layout after the last command recorded through transitionImage(); the helpers keep it.
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;

    VkImage get() const { return image.get(); }
    explicit operator bool() const { return static_cast<bool>(image); }
};

Image createImage(const Context& ctx, const ImageDesc& desc);

bool isDepthFormat(VkFormat format);
// Bytes per texel of the formats the project uses (colour, depth, r/rg/rgba 8/16/32).
uint32_t formatTexelSize(VkFormat format);

// Records a full barrier on `image` from its tracked layout to `newLayout` (all prior commands →
// all later commands). Simple and always correct; hot paths use imageBarrier() with exact stages.
void transitionImage(VkCommandBuffer cmd, Image& image, VkImageLayout newLayout);

// Records an image barrier with explicit stages and accesses; updates the tracked layout.
void imageBarrier(VkCommandBuffer cmd, Image& image, VkImageLayout newLayout,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// The same for an image the caller does not track (e.g. a swapchain's), colour aspect, from
// `oldLayout`.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout oldLayout,
                  VkImageLayout newLayout, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);
// The same for the aspects `aspect` of an untracked image (a host's depth and stencil).
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                  VkImageLayout oldLayout, VkImageLayout newLayout, VkPipelineStageFlags2 srcStage,
                  VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess);

// One dependency for several colour images that move together from `oldLayout` to `newLayout`,
// with a global memory barrier of the same stages and accesses (for buffers written or read on
// either side): one vkCmdPipelineBarrier2 however many images. Layouts are not tracked.
void imageBarriers(VkCommandBuffer cmd, std::span<const VkImage> images, VkImageLayout oldLayout,
                   VkImageLayout newLayout, VkPipelineStageFlags2 srcStage,
                   VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                   VkAccessFlags2 dstAccess);

// Records a global memory barrier (buffers, and images that keep their layout).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// Tightly packed texels of the whole image (first mip and layer), e.g. RGBA8 rows top to bottom
// for a colour target or 32-bit floats for a D32 depth target. Waits; leaves the image in
// `layoutAfter` (its previous layout when UNDEFINED is passed).
std::vector<std::byte> readImage(const Context& ctx, Image& image,
                                 VkImageLayout layoutAfter = VK_IMAGE_LAYOUT_UNDEFINED);

// Fills the whole image with tightly packed texels; leaves it in `layoutAfter`.
void uploadImage(const Context& ctx, Image& image, std::span<const std::byte> texels,
                 VkImageLayout layoutAfter);

UniqueSampler createSampler(const Context& ctx, VkFilter filter, VkSamplerAddressMode addressMode);

} // namespace mfx::gpu
