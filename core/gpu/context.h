// The Vulkan context: instance, chosen physical device, logical device, queues, limits and the
// optional features the project uses. One Context is created by the program (or adopted from a
// host program's device by the runtime library, include/motionfx/motionfx.h) and passed
// explicitly as the first argument to everything that touches the GPU; there are no globals.
//
// Device choice: a real GPU first (discrete, then integrated, then virtual), else a CPU
// implementation such as Mesa's lavapipe ("llvmpipe"). ContextOptions::deviceName, or the
// environment variable MOTIONFX_DEVICE when that is empty, picks a device by a case-insensitive
// substring of its name instead.
#pragma once

#include "core/gpu/handle.h"
#include "core/result.h"

#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>
#include <vulkan/vulkan.h>

namespace mfx::gpu {

// Environment variable naming the device (substring), used when no --device is given.
inline constexpr const char* kDeviceEnvironmentVariable = "MOTIONFX_DEVICE";

struct ProgramObjects; // core/gpu/program.h

struct ContextOptions {
    std::string deviceName;      // case-insensitive substring; empty: $MOTIONFX_DEVICE, then best
    bool validation = false;     // enable VK_LAYER_KHRONOS_validation and record its errors
    bool printValidation = true; // also print each recorded validation message to stderr
    std::vector<const char*> instanceExtensions; // extra ones (e.g. window surfaces)
    std::vector<const char*> deviceExtensions;   // extra ones (e.g. swapchain)
};

// Optional capabilities, enabled on the device whenever the device has them.
struct DeviceFeatures {
    bool geometryShader = false;
    bool transformFeedback = false;        // VK_EXT_transform_feedback
    bool geometryStreams = false;          // ... with multiple vertex streams
    bool shaderFloat16 = false;            // fp16 arithmetic in shaders
    bool storageBuffer16BitAccess = false; // fp16/int16 in storage buffers
    bool bufferFloat32AtomicAdd = false;   // VK_EXT_shader_atomic_float on buffers
    bool imageFloat32AtomicAdd = false;    // ... on storage images
    bool storageImageReadWithoutFormat = false;
    bool storageImageWriteWithoutFormat = false;
    bool fillModeNonSolid = false;
    bool wideLines = false;
    bool samplerAnisotropy = false;
    bool timestamps = false; // timestamp queries on the graphics/compute queue
};

struct Queue {
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t family = 0;
};

// A device the host application made and keeps (the runtime library, include/motionfx/motionfx.h):
// its handles, a queue of a family with graphics and compute, and what it was created with.
struct AdoptedDevice {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkQueue queue = VK_NULL_HANDLE;
    const VkPhysicalDeviceFeatures2* enabledFeatures = nullptr; // and the structs chained to it
    std::vector<std::string> enabledExtensions;
};

// The device extensions motionfx needs beyond Vulkan 1.3 (a Context made by create() enables them).
std::span<const char* const> requiredDeviceExtensions();

enum class MessageSeverity { Warning, Error };

struct ValidationMessage {
    MessageSeverity severity;
    std::string text;
};

// What one physical device is, as `motionfx info` reports it.
struct DeviceInfo {
    std::string name;
    std::string driverName;
    std::string driverInfo;
    uint32_t apiVersion = 0;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    bool isCpu() const { return type == VK_PHYSICAL_DEVICE_TYPE_CPU; }
};

std::string versionString(uint32_t apiVersion);
const char* toString(VkPhysicalDeviceType type);

class Context {
public:
    // Creates instance and device. Fails with a readable reason when there is no Vulkan driver, no
    // device matches the requested name, no device meets the requirements (Vulkan 1.3 with dynamic
    // rendering and synchronization2, push descriptors, a queue with graphics and compute), or
    // validation was asked for but the layer is not installed.
    static Result<std::unique_ptr<Context>> create(const ContextOptions& options);
    // Borrows the host's device: nothing of it is destroyed with the Context (its queue is waited
    // for, then what the Context made goes). Fails, naming every one that is missing, unless the
    // device has Vulkan 1.3, the queue's family graphics and compute, and was created with
    // dynamicRendering, synchronization2, geometryShader and requiredDeviceExtensions(). The
    // optional features are those the host enabled. No validation hook: the host's own reports.
    static Result<std::unique_ptr<Context>> adopt(const AdoptedDevice& host);

    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
    VkDevice device() const { return device_; }

    // The graphics queue's family also supports compute. The compute queue is a second queue of
    // the same family when the family has one, else the same queue; one family means resources
    // never need ownership transfers between them.
    const Queue& graphicsQueue() const { return graphicsQueue_; }
    const Queue& computeQueue() const { return computeQueue_; }

    const DeviceInfo& info() const { return info_; }
    const DeviceFeatures& features() const { return features_; }
    const VkPhysicalDeviceLimits& limits() const { return properties_.limits; }
    const VkPhysicalDeviceMemoryProperties& memoryProperties() const { return memory_; }
    double timestampPeriodNs() const { return double(properties_.limits.timestampPeriod); }
    bool validationEnabled() const { return validation_; }

    // Pool for one-shot command buffers on the graphics queue (see commands.h).
    VkCommandPool oneShotPool() const { return oneShotPool_.get(); }

    // Validation messages (errors, and warnings) recorded by the debug messenger since the last
    // clear. Tests assert that no errors were recorded.
    std::vector<ValidationMessage> validationMessages() const;
    size_t validationErrorCount() const;
    void clearValidationMessages();

    // Index of a memory type allowed by `typeBits` with all `required` flags, preferring one that
    // also has `preferred`; UINT32_MAX when none.
    uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                            VkMemoryPropertyFlags preferred = 0) const;

    // Gives a handle a name in validation messages and debuggers (no-op without validation).
    void setDebugName(VkObjectType type, uint64_t handle, const char* name) const;

    // Names of all physical devices, for error messages and `motionfx info --list`.
    std::vector<DeviceInfo> listDevices() const;

    void waitIdle() const;

    // A device-level command of an extension (nullptr when the device lacks it).
    PFN_vkVoidFunction deviceFunction(const char* name) const;
    // Resources are pushed when a program is bound (VK_KHR_push_descriptor, core/gpu/program.h).
    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet() const { return pushDescriptorSet_; }
    uint32_t maxPushDescriptors() const { return maxPushDescriptors_; }

    // The Vulkan objects of the programs made on this Context, by their description's key
    // (core/gpu/program.cpp): null when none was made yet; kept until the Context goes.
    std::shared_ptr<const ProgramObjects> findProgram(const std::string& key) const;
    void keepProgram(const std::string& key, std::shared_ptr<const ProgramObjects> objects) const;

private:
    Context() = default;
    // After the device and queues: the push-descriptor entry point and limit, the one-shot pool.
    Status finishDevice();
    static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    Queue graphicsQueue_;
    Queue computeQueue_;
    DeviceInfo info_;
    DeviceFeatures features_;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memory_{};
    bool validation_ = false;
    bool ownsDevice_ = true; // false: adopt()ed, the host's instance and device
    bool printValidation_ = true;
    mutable std::mutex programsMutex_;
    mutable std::unordered_map<std::string, std::shared_ptr<const ProgramObjects>> programs_;
    UniqueCommandPool oneShotPool_;
    PFN_vkSetDebugUtilsObjectNameEXT setObjectName_ = nullptr;
    PFN_vkCmdPushDescriptorSetKHR pushDescriptorSet_ = nullptr;
    uint32_t maxPushDescriptors_ = 0;

    mutable std::mutex messagesMutex_;
    std::vector<ValidationMessage> messages_;
};

} // namespace mfx::gpu
