#include "core/gpu/resources.h"

#include "core/gpu/check.h"
#include "core/gpu/commands.h"
#include "core/gpu/context.h"

#include <cstring>
#include <stdexcept>
#include <string>

namespace mfx::gpu {

namespace {

UniqueMemory allocate(const Context& ctx, const VkMemoryRequirements& requirements,
                      MemoryUsage usage, bool* hostVisible) {
    uint32_t type = UINT32_MAX;
    switch (usage) {
    case MemoryUsage::DeviceLocal:
        type = ctx.findMemoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        if (type == UINT32_MAX) type = ctx.findMemoryType(requirements.memoryTypeBits, 0);
        break;
    case MemoryUsage::Upload:
        type = ctx.findMemoryType(requirements.memoryTypeBits,
                                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                      VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        break;
    case MemoryUsage::Readback:
        type = ctx.findMemoryType(requirements.memoryTypeBits,
                                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                      VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                                  VK_MEMORY_PROPERTY_HOST_CACHED_BIT);
        break;
    }
    if (type == UINT32_MAX)
        throwVulkanError(VK_ERROR_FEATURE_NOT_PRESENT, "findMemoryType", __FILE__, __LINE__);
    const VkMemoryPropertyFlags flags = ctx.memoryProperties().memoryTypes[type].propertyFlags;
    // Mapping needs coherence here: the helpers never flush or invalidate.
    *hostVisible = (flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) &&
                   (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);

    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = requirements.size;
    info.memoryTypeIndex = type;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkAllocateMemory(ctx.device(), &info, nullptr, &memory));
    return UniqueMemory(ctx.device(), memory);
}

VkImageAspectFlags aspectOf(VkFormat format) {
    switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
        return VK_IMAGE_ASPECT_DEPTH_BIT;
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
        return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    default:
        return VK_IMAGE_ASPECT_COLOR_BIT;
    }
}

} // namespace

Buffer createBuffer(const Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                    MemoryUsage memory, const char* debugName) {
    if (size == 0) throw std::invalid_argument("createBuffer: size must be positive");
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer handle = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateBuffer(ctx.device(), &info, nullptr, &handle));
    Buffer buffer;
    buffer.buffer = UniqueBuffer(ctx.device(), handle);
    buffer.size = size;
    ctx.setDebugName(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(handle), debugName);

    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(ctx.device(), handle, &requirements);
    bool hostVisible = false;
    buffer.memory = allocate(ctx, requirements, memory, &hostVisible);
    MFX_VK_CHECK(vkBindBufferMemory(ctx.device(), handle, buffer.memory.get(), 0));
    if (hostVisible)
        MFX_VK_CHECK(
            vkMapMemory(ctx.device(), buffer.memory.get(), 0, VK_WHOLE_SIZE, 0, &buffer.mapped));
    return buffer;
}

void uploadBuffer(const Context& ctx, const Buffer& buffer, std::span<const std::byte> bytes,
                  VkDeviceSize offset) {
    if (offset + bytes.size() > buffer.size)
        throw std::out_of_range("uploadBuffer: " + std::to_string(bytes.size()) +
                                " bytes at offset " + std::to_string(offset) +
                                " overrun a buffer of " + std::to_string(buffer.size));
    if (bytes.empty()) return;
    if (buffer.mapped != nullptr) {
        std::memcpy(static_cast<std::byte*>(buffer.mapped) + offset, bytes.data(), bytes.size());
        return;
    }
    Buffer staging = createBuffer(ctx, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                  MemoryUsage::Upload, "upload staging");
    std::memcpy(staging.mapped, bytes.data(), bytes.size());
    submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, offset, bytes.size()};
        vkCmdCopyBuffer(cmd, staging.get(), buffer.get(), 1, &region);
    });
}

std::vector<std::byte> readBuffer(const Context& ctx, const Buffer& buffer) {
    std::vector<std::byte> bytes(buffer.size);
    if (buffer.mapped != nullptr) {
        // The caller has waited for the GPU work that wrote it; coherent memory needs nothing more.
        std::memcpy(bytes.data(), buffer.mapped, bytes.size());
        return bytes;
    }
    Buffer staging = createBuffer(ctx, buffer.size, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  MemoryUsage::Readback, "readback staging");
    submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, buffer.size};
        vkCmdCopyBuffer(cmd, buffer.get(), staging.get(), 1, &region);
    });
    std::memcpy(bytes.data(), staging.mapped, bytes.size());
    return bytes;
}

bool isDepthFormat(VkFormat format) {
    return (aspectOf(format) & VK_IMAGE_ASPECT_DEPTH_BIT) != 0;
}

uint32_t formatTexelSize(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R8_UINT:
        return 1;
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R8G8_UNORM:
    case VK_FORMAT_D16_UNORM:
        return 2;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32_SINT:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
        return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
        return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
        return 16;
    default:
        throw std::invalid_argument("formatTexelSize: format " + std::to_string(format) +
                                    " is not one the project uses");
    }
}

Image createImage(const Context& ctx, const ImageDesc& desc) {
    const bool is3D = desc.is3D || desc.extent.depth > 1;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = is3D ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
    info.format = desc.format;
    info.extent = desc.extent;
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = desc.samples;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = desc.usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage handle = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateImage(ctx.device(), &info, nullptr, &handle));

    Image image;
    image.image = UniqueImage(ctx.device(), handle);
    image.format = desc.format;
    image.extent = desc.extent;
    image.aspect = aspectOf(desc.format);
    image.samples = desc.samples;
    ctx.setDebugName(VK_OBJECT_TYPE_IMAGE, reinterpret_cast<uint64_t>(handle), desc.debugName);

    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(ctx.device(), handle, &requirements);
    bool hostVisible = false;
    image.memory = allocate(ctx, requirements, MemoryUsage::DeviceLocal, &hostVisible);
    MFX_VK_CHECK(vkBindImageMemory(ctx.device(), handle, image.memory.get(), 0));

    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = handle;
    viewInfo.viewType = is3D ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = desc.format;
    viewInfo.subresourceRange = {image.aspect & ~VK_IMAGE_ASPECT_STENCIL_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateImageView(ctx.device(), &viewInfo, nullptr, &view));
    image.view = UniqueImageView(ctx.device(), view);
    return image;
}

namespace {

VkImageMemoryBarrier2 layoutChange(VkImage image, VkImageAspectFlags aspect,
                                   VkImageLayout oldLayout, VkImageLayout newLayout,
                                   VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = srcStage;
    barrier.srcAccessMask = srcAccess;
    barrier.dstStageMask = dstStage;
    barrier.dstAccessMask = dstAccess;
    barrier.oldLayout = oldLayout;
    barrier.newLayout = newLayout;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {aspect, 0, 1, 0, 1};
    return barrier;
}

void layoutBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                   VkImageLayout oldLayout, VkImageLayout newLayout, VkPipelineStageFlags2 srcStage,
                   VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                   VkAccessFlags2 dstAccess) {
    const VkImageMemoryBarrier2 barrier =
        layoutChange(image, aspect, oldLayout, newLayout, srcStage, srcAccess, dstStage, dstAccess);
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

} // namespace

void imageBarriers(VkCommandBuffer cmd, std::span<const VkImage> images, VkImageLayout oldLayout,
                   VkImageLayout newLayout, VkPipelineStageFlags2 srcStage,
                   VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                   VkAccessFlags2 dstAccess) {
    VkMemoryBarrier2 memory{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    memory.srcStageMask = srcStage;
    memory.srcAccessMask = srcAccess;
    memory.dstStageMask = dstStage;
    memory.dstAccessMask = dstAccess;
    std::vector<VkImageMemoryBarrier2> barriers;
    for (VkImage image : images)
        barriers.push_back(layoutChange(image, VK_IMAGE_ASPECT_COLOR_BIT, oldLayout, newLayout,
                                        srcStage, srcAccess, dstStage, dstAccess));
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &memory;
    dependency.imageMemoryBarrierCount = uint32_t(barriers.size());
    dependency.pImageMemoryBarriers = barriers.data();
    vkCmdPipelineBarrier2(cmd, &dependency);
}

void imageBarrier(VkCommandBuffer cmd, Image& image, VkImageLayout newLayout,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    layoutBarrier(cmd, image.get(), image.aspect, image.layout, newLayout, srcStage, srcAccess,
                  dstStage, dstAccess);
    image.layout = newLayout;
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout oldLayout,
                  VkImageLayout newLayout, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    layoutBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, oldLayout, newLayout, srcStage, srcAccess,
                  dstStage, dstAccess);
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                  VkImageLayout oldLayout, VkImageLayout newLayout, VkPipelineStageFlags2 srcStage,
                  VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess) {
    layoutBarrier(cmd, image, aspect, oldLayout, newLayout, srcStage, srcAccess, dstStage,
                  dstAccess);
}

void transitionImage(VkCommandBuffer cmd, Image& image, VkImageLayout newLayout) {
    imageBarrier(cmd, image, newLayout, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                 VK_ACCESS_2_MEMORY_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                 VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = srcStage;
    barrier.srcAccessMask = srcAccess;
    barrier.dstStageMask = dstStage;
    barrier.dstAccessMask = dstAccess;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

namespace {
VkDeviceSize imageByteSize(const Image& image) {
    return VkDeviceSize(formatTexelSize(image.format)) * image.extent.width * image.extent.height *
           image.extent.depth;
}

VkBufferImageCopy wholeImageRegion(const Image& image) {
    VkBufferImageCopy region{};
    region.imageSubresource = {image.aspect & ~VK_IMAGE_ASPECT_STENCIL_BIT, 0, 0, 1};
    region.imageExtent = image.extent;
    return region;
}
} // namespace

std::vector<std::byte> readImage(const Context& ctx, Image& image, VkImageLayout layoutAfter) {
    if (image.samples != VK_SAMPLE_COUNT_1_BIT)
        throw std::invalid_argument("readImage: a multisampled image must be resolved first");
    const VkImageLayout finalLayout =
        layoutAfter == VK_IMAGE_LAYOUT_UNDEFINED ? image.layout : layoutAfter;
    Buffer staging = createBuffer(ctx, imageByteSize(image), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  MemoryUsage::Readback, "image readback staging");
    submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        const VkBufferImageCopy region = wholeImageRegion(image);
        vkCmdCopyImageToBuffer(cmd, image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               staging.get(), 1, &region);
        if (finalLayout != VK_IMAGE_LAYOUT_UNDEFINED && finalLayout != image.layout)
            transitionImage(cmd, image, finalLayout);
    });
    std::vector<std::byte> bytes(staging.size);
    std::memcpy(bytes.data(), staging.mapped, bytes.size());
    return bytes;
}

void uploadImage(const Context& ctx, Image& image, std::span<const std::byte> texels,
                 VkImageLayout layoutAfter) {
    if (texels.size() != imageByteSize(image))
        throw std::invalid_argument("uploadImage: " + std::to_string(texels.size()) +
                                    " bytes for an image of " +
                                    std::to_string(imageByteSize(image)));
    Buffer staging = createBuffer(ctx, texels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                  MemoryUsage::Upload, "image upload staging");
    std::memcpy(staging.mapped, texels.data(), texels.size());
    submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        image.layout = VK_IMAGE_LAYOUT_UNDEFINED; // contents are replaced entirely
        transitionImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        const VkBufferImageCopy region = wholeImageRegion(image);
        vkCmdCopyBufferToImage(cmd, staging.get(), image.get(),
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        transitionImage(cmd, image, layoutAfter);
    });
}

UniqueSampler createSampler(const Context& ctx, VkFilter filter, VkSamplerAddressMode addressMode) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = filter;
    info.minFilter = filter;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = addressMode;
    info.addressModeV = addressMode;
    info.addressModeW = addressMode;
    info.maxLod = 0.0f;
    info.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    VkSampler sampler = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateSampler(ctx.device(), &info, nullptr, &sampler));
    return UniqueSampler(ctx.device(), sampler);
}

} // namespace mfx::gpu
