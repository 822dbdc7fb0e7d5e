// A swapchain on a window surface (the surface is made by the caller, e.g. with GLFW): images
// that a frame is copied into and presented from, with the semaphores that order acquire, the
// frame's commands and presentation. The Context must have been created with the surface's
// instance extensions and VK_KHR_swapchain (ContextOptions).
#pragma once

#include "core/gpu/handle.h"
#include "core/result.h"

#include <cstdint>
#include <memory>
#include <vector>
#include <vulkan/vulkan.h>

namespace mfx::gpu {

class Context;

class Swapchain {
public:
    Swapchain() = default;
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // Takes ownership of `surface`. Fails (with the reason) when the graphics queue cannot
    // present to it or it offers no usable format. `width` x `height` is used where the surface
    // leaves the size to the swapchain.
    static Result<std::unique_ptr<Swapchain>> create(const Context& ctx, VkSurfaceKHR surface,
                                                     uint32_t width, uint32_t height);

    // Rebuilds the images for a new size (after a resize, or when present says out of date).
    void recreate(uint32_t width, uint32_t height);

    // Acquires the next image; false when the swapchain is out of date (recreate and try again).
    // `ready` is signalled when the image may be written.
    bool acquire(uint32_t& index, VkSemaphore& ready);
    // Presents image `index` once `finished` is signalled; false when out of date or suboptimal.
    bool present(uint32_t index, VkSemaphore finished);

    VkImage image(uint32_t index) const { return images_[index]; }
    VkImageView view(uint32_t index) const { return views_[index].get(); }
    VkFormat format() const { return format_; }
    uint32_t imageCount() const { return uint32_t(images_.size()); }
    VkExtent2D extent() const { return extent_; }
    // Whether the images can be copied from (for screenshots).
    bool readable() const { return readable_; }
    // A semaphore per image for the frame's commands to signal before presentation.
    VkSemaphore renderFinished(uint32_t index) const { return finished_[index].get(); }

private:
    void build(uint32_t width, uint32_t height);
    void destroyImages();

    const Context* ctx_ = nullptr;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkColorSpaceKHR colourSpace_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    VkPresentModeKHR presentMode_ = VK_PRESENT_MODE_FIFO_KHR;
    VkExtent2D extent_{};
    bool readable_ = false;
    std::vector<VkImage> images_;
    std::vector<DeviceHandle<VkImageView, vkDestroyImageView>> views_;
    std::vector<UniqueSemaphore> acquired_; // one more than images, used round robin
    std::vector<UniqueSemaphore> finished_;
    uint32_t nextAcquire_ = 0;
};

} // namespace mfx::gpu
