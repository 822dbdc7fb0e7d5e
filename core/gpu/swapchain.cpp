#include "core/gpu/swapchain.h"

#include "core/gpu/check.h"
#include "core/gpu/context.h"

#include <algorithm>
#include <memory>

namespace mfx::gpu {

namespace {

UniqueSemaphore makeSemaphore(VkDevice device) {
    VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateSemaphore(device, &info, nullptr, &semaphore));
    return UniqueSemaphore(device, semaphore);
}

} // namespace

Result<std::unique_ptr<Swapchain>> Swapchain::create(const Context& ctx, VkSurfaceKHR surface,
                                                     uint32_t width, uint32_t height) {
    std::unique_ptr<Swapchain> s(new Swapchain());
    s->ctx_ = &ctx;
    s->surface_ = surface;
    VkBool32 supported = VK_FALSE;
    MFX_VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(
        ctx.physicalDevice(), ctx.graphicsQueue().family, surface, &supported));
    if (!supported)
        return Error{ctx.info().name + "'s graphics queue cannot present to this window"};
    uint32_t count = 0;
    MFX_VK_CHECK(
        vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice(), surface, &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    MFX_VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice(), surface, &count,
                                                      formats.data()));
    // An sRGB format, so the (linear-blended, sRGB-encoded) frame is copied without conversion
    // of meaning; else the first offered.
    auto srgb = std::find_if(formats.begin(), formats.end(), [](const VkSurfaceFormatKHR& f) {
        return (f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) &&
               f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    });
    if (formats.empty()) return Error{"the window surface offers no image format"};
    const VkSurfaceFormatKHR chosen = srgb != formats.end() ? *srgb : formats.front();
    s->format_ = chosen.format;
    s->colourSpace_ = chosen.colorSpace;
    // Without vertical sync where the surface allows it, so the on-screen frame time is the
    // frame's own; FIFO (always there) otherwise.
    MFX_VK_CHECK(
        vkGetPhysicalDeviceSurfacePresentModesKHR(ctx.physicalDevice(), surface, &count, nullptr));
    std::vector<VkPresentModeKHR> modes(count);
    MFX_VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(ctx.physicalDevice(), surface, &count,
                                                           modes.data()));
    for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
        if (std::find(modes.begin(), modes.end(), wanted) != modes.end()) {
            s->presentMode_ = wanted;
            break;
        }
    s->build(width, height);
    return s;
}

Swapchain::~Swapchain() {
    if (!ctx_) return;
    vkDeviceWaitIdle(ctx_->device());
    destroyImages();
    if (swapchain_) vkDestroySwapchainKHR(ctx_->device(), swapchain_, nullptr);
    if (surface_) vkDestroySurfaceKHR(ctx_->instance(), surface_, nullptr);
}

void Swapchain::destroyImages() {
    views_.clear();
    acquired_.clear();
    finished_.clear();
    images_.clear();
}

void Swapchain::recreate(uint32_t width, uint32_t height) {
    vkDeviceWaitIdle(ctx_->device());
    build(width, height);
}

void Swapchain::build(uint32_t width, uint32_t height) {
    const VkDevice device = ctx_->device();
    VkSurfaceCapabilitiesKHR caps{};
    MFX_VK_CHECK(
        vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx_->physicalDevice(), surface_, &caps));
    if (caps.currentExtent.width != UINT32_MAX) {
        extent_ = caps.currentExtent;
    } else {
        extent_.width = std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent_.height = std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    uint32_t imageCount = caps.minImageCount + 1;
    if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);
    readable_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = surface_;
    info.minImageCount = imageCount;
    info.imageFormat = format_;
    info.imageColorSpace = colourSpace_;
    info.imageExtent = extent_;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                      (readable_ ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                              ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                              : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha &
                                                            -caps.supportedCompositeAlpha);
    info.presentMode = presentMode_;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateSwapchainKHR(device, &info, nullptr, &created));
    destroyImages();
    if (swapchain_) vkDestroySwapchainKHR(device, swapchain_, nullptr);
    swapchain_ = created;

    uint32_t count = 0;
    MFX_VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain_, &count, nullptr));
    images_.resize(count);
    MFX_VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain_, &count, images_.data()));
    for (VkImage image : images_) {
        VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view.image = image;
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = format_;
        view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView handle = VK_NULL_HANDLE;
        MFX_VK_CHECK(vkCreateImageView(device, &view, nullptr, &handle));
        views_.emplace_back(device, handle);
        finished_.push_back(makeSemaphore(device));
    }
    for (uint32_t i = 0; i <= count; ++i)
        acquired_.push_back(makeSemaphore(device));
    nextAcquire_ = 0;
}

bool Swapchain::acquire(uint32_t& index, VkSemaphore& ready) {
    ready = acquired_[nextAcquire_].get();
    const VkResult result = vkAcquireNextImageKHR(ctx_->device(), swapchain_, UINT64_MAX, ready,
                                                  VK_NULL_HANDLE, &index);
    if (result == VK_ERROR_OUT_OF_DATE_KHR) return false;
    if (result != VK_SUBOPTIMAL_KHR) MFX_VK_CHECK(result);
    nextAcquire_ = (nextAcquire_ + 1) % uint32_t(acquired_.size());
    return true;
}

bool Swapchain::present(uint32_t index, VkSemaphore finished) {
    VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &finished;
    info.swapchainCount = 1;
    info.pSwapchains = &swapchain_;
    info.pImageIndices = &index;
    const VkResult result = vkQueuePresentKHR(ctx_->graphicsQueue().queue, &info);
    if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR) return false;
    MFX_VK_CHECK(result);
    return true;
}

} // namespace mfx::gpu
