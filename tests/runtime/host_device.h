// A host application's Vulkan device, made with plain Vulkan calls as an engine would make it
// (the runtime library's tests; examples/host does the same in C): an instance of Vulkan 1.3, the
// first device with a graphics and compute queue family, and a device with the features and
// extensions the test asks for.
#pragma once

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
    std::vector<const char*> extensions;

private:
    HostDevice() = default;
};

} // namespace mfx::test
