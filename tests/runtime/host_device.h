// A host application's Vulkan device, made with plain Vulkan calls as an engine would make it
// (the runtime library's tests; examples/host does the same in C): an instance of Vulkan 1.3, the
// first device with a graphics and compute queue family, and a device with the features and
// extensions the test asks for.
#pragma once

#include "core/gpu/context.h"
#include "motionfx/motionfx.h"

#include <atomic>
#include <memory>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

namespace mfx::test {

struct HostDeviceOptions {
    bool pushDescriptor = true; // VK_KHR_push_descriptor
    bool geometryShader = true;
    bool dynamicRendering = true;
    bool synchronization2 = true;
    // dynamicRendering and synchronization2 through their own feature structs instead of
    // VkPhysicalDeviceVulkan13Features (the chain may not hold both).
    bool standaloneStructs = false;
};

class HostDevice {
public:
    // Null (with `why` set) when the machine has no such device.
    static std::unique_ptr<HostDevice> make(const HostDeviceOptions& options, std::string& why);
    ~HostDevice();
    HostDevice(const HostDevice&) = delete;
    HostDevice& operator=(const HostDevice&) = delete;

    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t family = 0;
    VkQueue queue = VK_NULL_HANDLE;
    std::string name;
    // What the device was created with (the chain is linked: features -> v11 -> v12 -> v13).
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    VkPhysicalDeviceVulkan11Features v11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceDynamicRenderingFeatures dynamicRendering{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
    VkPhysicalDeviceSynchronization2Features synchronization2{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES};
    std::vector<const char*> extensions;

    // With the validation layer installed the instance has it, and its errors are counted here
    // (and printed): what motionfx does on the host's device is checked as the program's is.
    bool validated() const { return messenger_ != VK_NULL_HANDLE; }
    uint32_t validationErrors() const { return errors_; }

private:
    HostDevice() = default;
    static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    std::atomic<uint32_t> errors_{0};
};

// The runtime's description of the host's device (no message callback unless given).
MfxRuntimeDesc runtimeDesc(const HostDevice& host, MfxMessageCallback callback = nullptr,
                           void* user = nullptr);

// The host's device as the project's own gpu::Context adopts it (a test's view of the device the
// runtime runs on).
gpu::AdoptedDevice adoptedDevice(const HostDevice& host);

} // namespace mfx::test
