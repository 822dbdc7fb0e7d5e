#include "tests/runtime/host_device.h"

#include <cstdio>
#include <cstring>

namespace mfx::test {

VKAPI_ATTR VkBool32 VKAPI_CALL HostDevice::onMessage(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        ++static_cast<HostDevice*>(user)->errors_;
        std::fprintf(stderr, "host validation: %s\n", data->pMessage);
    }
    return VK_FALSE;
}

std::unique_ptr<HostDevice> HostDevice::make(const HostDeviceOptions& options, std::string& why) {
    std::unique_ptr<HostDevice> host(new HostDevice());
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "motionfx runtime test host";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instanceInfo.pApplicationInfo = &app;
    uint32_t layerCount = 0;
    vkEnumerateInstanceLayerProperties(&layerCount, nullptr);
    std::vector<VkLayerProperties> layers(layerCount);
    vkEnumerateInstanceLayerProperties(&layerCount, layers.data());
    const char* validation = "VK_LAYER_KHRONOS_validation";
    const char* debugUtils = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    bool validate = false;
    for (const VkLayerProperties& layer : layers)
        validate = validate || std::strcmp(layer.layerName, validation) == 0;
    if (validate) {
        instanceInfo.enabledLayerCount = 1;
        instanceInfo.ppEnabledLayerNames = &validation;
        instanceInfo.enabledExtensionCount = 1;
        instanceInfo.ppEnabledExtensionNames = &debugUtils;
    }
    if (vkCreateInstance(&instanceInfo, nullptr, &host->instance) != VK_SUCCESS) {
        why = "no Vulkan 1.3 instance";
        return nullptr;
    }
    if (validate) {
        VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
            VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
        messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                    VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
        messengerInfo.pfnUserCallback = &HostDevice::onMessage;
        messengerInfo.pUserData = host.get();
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(host->instance, "vkCreateDebugUtilsMessengerEXT"));
        if (create != nullptr) create(host->instance, &messengerInfo, nullptr, &host->messenger_);
    }
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(host->instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(host->instance, &count, devices.data());
    for (VkPhysicalDevice candidate : devices) {
        uint32_t familyCount = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &familyCount, nullptr);
        std::vector<VkQueueFamilyProperties> families(familyCount);
        vkGetPhysicalDeviceQueueFamilyProperties(candidate, &familyCount, families.data());
        for (uint32_t f = 0; f < familyCount && host->physicalDevice == VK_NULL_HANDLE; ++f)
            if ((families[f].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
                (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
                host->physicalDevice = candidate;
                host->family = f;
            }
    }
    if (host->physicalDevice == VK_NULL_HANDLE) {
        why = "no device with a graphics and compute queue family";
        return nullptr;
    }
    VkPhysicalDeviceProperties properties{};
    vkGetPhysicalDeviceProperties(host->physicalDevice, &properties);
    host->name = properties.deviceName;

    host->features.pNext = &host->v11;
    host->v11.pNext = &host->v12;
    host->features.features.geometryShader = options.geometryShader ? VK_TRUE : VK_FALSE;
    if (options.standaloneStructs) {
        host->v12.pNext = &host->dynamicRendering;
        host->dynamicRendering.pNext = &host->synchronization2;
        host->dynamicRendering.dynamicRendering = options.dynamicRendering ? VK_TRUE : VK_FALSE;
        host->synchronization2.synchronization2 = options.synchronization2 ? VK_TRUE : VK_FALSE;
    } else {
        host->v12.pNext = &host->v13;
        host->v13.dynamicRendering = options.dynamicRendering ? VK_TRUE : VK_FALSE;
        host->v13.synchronization2 = options.synchronization2 ? VK_TRUE : VK_FALSE;
    }
    if (options.pushDescriptor) host->extensions.push_back(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = host->family;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.pNext = &host->features;
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    deviceInfo.enabledExtensionCount = uint32_t(host->extensions.size());
    deviceInfo.ppEnabledExtensionNames = host->extensions.data();
    if (vkCreateDevice(host->physicalDevice, &deviceInfo, nullptr, &host->device) != VK_SUCCESS) {
        why = "could not create the device on " + host->name;
        return nullptr;
    }
    vkGetDeviceQueue(host->device, host->family, 0, &host->queue);
    return host;
}

HostDevice::~HostDevice() {
    if (device != VK_NULL_HANDLE) vkDestroyDevice(device, nullptr);
    if (messenger_ != VK_NULL_HANDLE) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy != nullptr) destroy(instance, messenger_, nullptr);
    }
    if (instance != VK_NULL_HANDLE) vkDestroyInstance(instance, nullptr);
}

MfxRuntimeDesc runtimeDesc(const HostDevice& host, MfxMessageCallback callback, void* user) {
    MfxRuntimeDesc desc{};
    desc.structVersion = MFX_RUNTIME_DESC_VERSION;
    desc.instance = host.instance;
    desc.physicalDevice = host.physicalDevice;
    desc.device = host.device;
    desc.queueFamilyIndex = host.family;
    desc.queue = host.queue;
    desc.enabledFeatures = &host.features;
    desc.enabledExtensionCount = uint32_t(host.extensions.size());
    desc.enabledExtensionNames = host.extensions.data();
    desc.messageCallback = callback;
    desc.messageUser = user;
    return desc;
}

gpu::AdoptedDevice adoptedDevice(const HostDevice& host) {
    gpu::AdoptedDevice adopted;
    adopted.instance = host.instance;
    adopted.physicalDevice = host.physicalDevice;
    adopted.device = host.device;
    adopted.queueFamily = host.family;
    adopted.queue = host.queue;
    adopted.enabledFeatures = &host.features;
    for (const char* extension : host.extensions)
        adopted.enabledExtensions.emplace_back(extension);
    return adopted;
}

} // namespace mfx::test
