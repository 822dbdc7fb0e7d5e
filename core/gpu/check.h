// Failure handling for Vulkan calls.
//
// Set-up that a user can make fail (no driver, no matching device, missing layer) reports through
// mfx::Result. Any other failed Vulkan call is a bug or an exhausted machine: MFX_VK_CHECK throws
// VulkanError carrying file:line, the call and the VkResult, so it stops loudly; the programs catch
// it at the top and print it as one line.
#pragma once

#include <stdexcept>
#include <string>
#include <vulkan/vulkan.h>

namespace mfx::gpu {

const char* toString(VkResult result);

class VulkanError : public std::runtime_error {
public:
    VulkanError(const std::string& what, VkResult result)
        : std::runtime_error(what), result_(result) {}
    VkResult result() const { return result_; }

private:
    VkResult result_;
};

[[noreturn]] void throwVulkanError(VkResult result, const char* call, const char* file, int line);

} // namespace mfx::gpu

#define MFX_VK_CHECK(call)                                                                         \
    do {                                                                                           \
        const VkResult mfx_vk_result_ = (call);                                                    \
        if (mfx_vk_result_ != VK_SUCCESS)                                                          \
            ::mfx::gpu::throwVulkanError(mfx_vk_result_, #call, __FILE__, __LINE__);               \
    } while (false)
