#include "core/gpu/context.h"

#include "core/gpu/check.h"
#include "core/gpu/program.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <sstream>

namespace mfx::gpu {

const char* toString(VkResult result) {
    switch (result) {
#define MFX_CASE(x)                                                                                \
    case x:                                                                                        \
        return #x
        MFX_CASE(VK_SUCCESS);
        MFX_CASE(VK_NOT_READY);
        MFX_CASE(VK_TIMEOUT);
        MFX_CASE(VK_EVENT_SET);
        MFX_CASE(VK_EVENT_RESET);
        MFX_CASE(VK_INCOMPLETE);
        MFX_CASE(VK_ERROR_OUT_OF_HOST_MEMORY);
        MFX_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY);
        MFX_CASE(VK_ERROR_INITIALIZATION_FAILED);
        MFX_CASE(VK_ERROR_DEVICE_LOST);
        MFX_CASE(VK_ERROR_MEMORY_MAP_FAILED);
        MFX_CASE(VK_ERROR_LAYER_NOT_PRESENT);
        MFX_CASE(VK_ERROR_EXTENSION_NOT_PRESENT);
        MFX_CASE(VK_ERROR_FEATURE_NOT_PRESENT);
        MFX_CASE(VK_ERROR_INCOMPATIBLE_DRIVER);
        MFX_CASE(VK_ERROR_TOO_MANY_OBJECTS);
        MFX_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED);
        MFX_CASE(VK_ERROR_FRAGMENTED_POOL);
        MFX_CASE(VK_ERROR_UNKNOWN);
        MFX_CASE(VK_ERROR_OUT_OF_POOL_MEMORY);
        MFX_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE);
        MFX_CASE(VK_ERROR_FRAGMENTATION);
        MFX_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS);
        MFX_CASE(VK_ERROR_SURFACE_LOST_KHR);
        MFX_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR);
        MFX_CASE(VK_SUBOPTIMAL_KHR);
        MFX_CASE(VK_ERROR_OUT_OF_DATE_KHR);
        MFX_CASE(VK_ERROR_VALIDATION_FAILED_EXT);
#undef MFX_CASE
    default:
        return "VkResult(unknown)";
    }
}

void throwVulkanError(VkResult result, const char* call, const char* file, int line) {
    std::ostringstream out;
    out << file << ":" << line << ": " << call << " failed with " << toString(result);
    throw VulkanError(out.str(), result);
}

std::string versionString(uint32_t apiVersion) {
    return std::to_string(VK_API_VERSION_MAJOR(apiVersion)) + "." +
           std::to_string(VK_API_VERSION_MINOR(apiVersion)) + "." +
           std::to_string(VK_API_VERSION_PATCH(apiVersion));
}

const char* toString(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return "CPU";
    default:
        return "other";
    }
}

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr uint32_t kRequiredApiVersion = VK_API_VERSION_1_3;

std::string lowercase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

bool hasInstanceLayer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, name) == 0;
    });
}

std::vector<std::string> instanceExtensionNames() {
    uint32_t count = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateInstanceExtensionProperties(nullptr, &count, extensions.data());
    std::vector<std::string> names;
    for (const auto& e : extensions)
        names.emplace_back(e.extensionName);
    return names;
}

std::vector<std::string> deviceExtensionNames(VkPhysicalDevice device) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
    std::vector<std::string> names;
    for (const auto& e : extensions)
        names.emplace_back(e.extensionName);
    return names;
}

bool contains(const std::vector<std::string>& names, const char* name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

DeviceInfo describe(VkPhysicalDevice device) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &driver;
    vkGetPhysicalDeviceProperties2(device, &properties);
    DeviceInfo info;
    info.name = properties.properties.deviceName;
    info.driverName = driver.driverName;
    info.driverInfo = driver.driverInfo;
    info.apiVersion = properties.properties.apiVersion;
    info.type = properties.properties.deviceType;
    return info;
}

int typeRank(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return 4;
    default:
        return 3;
    }
}

// The family used for graphics and compute, or UINT32_MAX.
uint32_t universalQueueFamily(VkPhysicalDevice device) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    for (uint32_t i = 0; i < count; ++i) {
        const VkQueueFlags wanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & wanted) == wanted) return i;
    }
    return UINT32_MAX;
}

// Feature structures chained for query and for enabling.
struct FeatureChain {
    VkPhysicalDeviceFeatures2 core{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    VkPhysicalDeviceVulkan11Features v11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
    VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceTransformFeedbackFeaturesEXT transformFeedback{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TRANSFORM_FEEDBACK_FEATURES_EXT};
    VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomicFloat{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};

    // Links the structures; the extension ones only when the extension is present.
    void link(bool withTransformFeedback, bool withAtomicFloat) {
        core.pNext = &v11;
        v11.pNext = &v12;
        v12.pNext = &v13;
        void** tail = &v13.pNext;
        if (withTransformFeedback) {
            *tail = &transformFeedback;
            tail = &transformFeedback.pNext;
        }
        if (withAtomicFloat) {
            *tail = &atomicFloat;
            tail = &atomicFloat.pNext;
        }
        *tail = nullptr;
    }
};

// The optional capabilities a device was created with (`enabled`); timestamps where its queue's
// family counts them.
DeviceFeatures recordedFeatures(const FeatureChain& enabled, bool hasTransformFeedback,
                                bool hasAtomicFloat, const VkQueueFamilyProperties& family,
                                const VkPhysicalDeviceLimits& limits) {
    const VkPhysicalDeviceFeatures& use = enabled.core.features;
    DeviceFeatures f;
    f.geometryShader = use.geometryShader;
    f.fillModeNonSolid = use.fillModeNonSolid;
    f.wideLines = use.wideLines;
    f.samplerAnisotropy = use.samplerAnisotropy;
    f.storageImageReadWithoutFormat = use.shaderStorageImageReadWithoutFormat;
    f.storageImageWriteWithoutFormat = use.shaderStorageImageWriteWithoutFormat;
    f.shaderFloat16 = enabled.v12.shaderFloat16;
    f.storageBuffer16BitAccess = enabled.v11.storageBuffer16BitAccess;
    f.transformFeedback = hasTransformFeedback && enabled.transformFeedback.transformFeedback;
    f.geometryStreams = hasTransformFeedback && enabled.transformFeedback.geometryStreams;
    f.bufferFloat32AtomicAdd = hasAtomicFloat && enabled.atomicFloat.shaderBufferFloat32AtomicAdd;
    f.imageFloat32AtomicAdd = hasAtomicFloat && enabled.atomicFloat.shaderImageFloat32AtomicAdd;
    f.timestamps = family.timestampValidBits > 0 && limits.timestampPeriod > 0;
    return f;
}

// The host's feature chain copied into ours (the structures it does not have stay all false).
FeatureChain copiedChain(const VkPhysicalDeviceFeatures2& host) {
    FeatureChain chain;
    chain.link(true, true);
    chain.core.features = host.features;
    VkBool32 dynamicRendering = VK_FALSE, synchronization2 = VK_FALSE;
    // Walks at most 64 structures: a chain that loops is the host's bug, not a hang of ours.
    const auto* next = static_cast<const VkBaseInStructure*>(host.pNext);
    for (int i = 0; next != nullptr && i < 64; ++i, next = next->pNext) {
        auto copy = [&](auto& into) {
            void* keep = into.pNext;
            std::memcpy(&into, next, sizeof into);
            into.pNext = keep;
        };
        switch (next->sType) {
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES:
            copy(chain.v11);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES:
            copy(chain.v12);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES:
            copy(chain.v13);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_TRANSFORM_FEEDBACK_FEATURES_EXT:
            copy(chain.transformFeedback);
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT:
            copy(chain.atomicFloat);
            break;
        // The 1.3 features a host may enable through their own structs instead.
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES:
            dynamicRendering |=
                reinterpret_cast<const VkPhysicalDeviceDynamicRenderingFeatures*>(next)
                    ->dynamicRendering;
            break;
        case VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SYNCHRONIZATION_2_FEATURES:
            synchronization2 |=
                reinterpret_cast<const VkPhysicalDeviceSynchronization2Features*>(next)
                    ->synchronization2;
            break;
        default:
            break;
        }
    }
    chain.v13.dynamicRendering |= dynamicRendering;
    chain.v13.synchronization2 |= synchronization2;
    return chain;
}

// Why `device` cannot be used, or empty when it can.
std::string unsuitableReason(VkPhysicalDevice device) {
    const DeviceInfo info = describe(device);
    if (info.apiVersion < kRequiredApiVersion)
        return "supports Vulkan " + versionString(info.apiVersion) + ", 1.3 is required";
    if (universalQueueFamily(device) == UINT32_MAX)
        return "has no queue family with both graphics and compute";
    FeatureChain chain;
    chain.link(false, false);
    vkGetPhysicalDeviceFeatures2(device, &chain.core);
    if (!chain.v13.dynamicRendering) return "lacks dynamicRendering";
    if (!chain.v13.synchronization2) return "lacks synchronization2";
    if (!contains(deviceExtensionNames(device), VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
        return std::string("lacks ") + VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME;
    return {};
}

} // namespace

Result<std::unique_ptr<Context>> Context::create(const ContextOptions& options) {
    std::unique_ptr<Context> ctx(new Context());
    ctx->validation_ = options.validation;
    ctx->printValidation_ = options.printValidation;

    // --- Instance ---------------------------------------------------------------------------
    uint32_t loaderVersion = VK_API_VERSION_1_0;
    vkEnumerateInstanceVersion(&loaderVersion);
    if (loaderVersion < kRequiredApiVersion)
        return Error{"the Vulkan loader supports only Vulkan " + versionString(loaderVersion) +
                     "; version 1.3 is required"};

    std::vector<const char*> layers;
    if (options.validation) {
        if (!hasInstanceLayer(kValidationLayer))
            return Error{"validation was requested but the Vulkan validation layer is not "
                         "installed (Debian package vulkan-validationlayers)"};
        layers.push_back(kValidationLayer);
    }

    const std::vector<std::string> available = instanceExtensionNames();
    std::vector<const char*> extensions = options.instanceExtensions;
    for (const char* name : extensions)
        if (!contains(available, name))
            return Error{std::string("the Vulkan instance lacks the extension ") + name};
    if (options.validation) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    VkInstanceCreateFlags instanceFlags = 0;
    if (contains(available, VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME)) {
        extensions.push_back(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);
        instanceFlags |= VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR;
    }

    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "motionfx";
    app.applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
    app.pEngineName = "motionfx";
    app.apiVersion = kRequiredApiVersion;

    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                    VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = &Context::debugCallback;
    messengerInfo.pUserData = ctx.get();

    // Synchronization validation catches missing barriers, the classic GPU-pipeline bug.
    VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT validationFeatures{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    validationFeatures.enabledValidationFeatureCount = 1;
    validationFeatures.pEnabledValidationFeatures = enables;
    validationFeatures.pNext = &messengerInfo;

    VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instanceInfo.pNext = options.validation ? &validationFeatures : nullptr;
    instanceInfo.flags = instanceFlags;
    instanceInfo.pApplicationInfo = &app;
    instanceInfo.enabledLayerCount = static_cast<uint32_t>(layers.size());
    instanceInfo.ppEnabledLayerNames = layers.data();
    instanceInfo.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    instanceInfo.ppEnabledExtensionNames = extensions.data();
    const VkResult instanceResult = vkCreateInstance(&instanceInfo, nullptr, &ctx->instance_);
    if (instanceResult == VK_ERROR_INCOMPATIBLE_DRIVER ||
        instanceResult == VK_ERROR_INITIALIZATION_FAILED)
        return Error{"no Vulkan driver was found (vkCreateInstance returned " +
                     std::string(toString(instanceResult)) +
                     "); install one, e.g. Mesa's CPU driver lavapipe (Debian package "
                     "mesa-vulkan-drivers)"};
    if (instanceResult != VK_SUCCESS)
        return Error{std::string("could not create a Vulkan instance: ") +
                     toString(instanceResult)};

    if (options.validation) {
        auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(ctx->instance_, "vkCreateDebugUtilsMessengerEXT"));
        ctx->setObjectName_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetInstanceProcAddr(ctx->instance_, "vkSetDebugUtilsObjectNameEXT"));
        if (createMessenger == nullptr || createMessenger(ctx->instance_, &messengerInfo, nullptr,
                                                          &ctx->messenger_) != VK_SUCCESS)
            return Error{"could not install the validation message hook"};
    }

    // --- Physical device ----------------------------------------------------------------------
    uint32_t deviceCount = 0;
    vkEnumeratePhysicalDevices(ctx->instance_, &deviceCount, nullptr);
    std::vector<VkPhysicalDevice> devices(deviceCount);
    vkEnumeratePhysicalDevices(ctx->instance_, &deviceCount, devices.data());
    if (devices.empty())
        return Error{"no Vulkan device was found; install a Vulkan driver, e.g. Mesa's CPU driver "
                     "lavapipe (Debian package mesa-vulkan-drivers)"};

    std::string wanted = options.deviceName;
    std::string wantedFrom = "--device";
    if (wanted.empty()) {
        if (const char* env = std::getenv(kDeviceEnvironmentVariable); env != nullptr && *env) {
            wanted = env;
            wantedFrom = kDeviceEnvironmentVariable;
        }
    }

    std::string allNames;
    std::string rejections;
    VkPhysicalDevice best = VK_NULL_HANDLE;
    int bestRank = 1 << 30;
    bool anyNameMatched = false;
    for (VkPhysicalDevice candidate : devices) {
        const DeviceInfo info = describe(candidate);
        allNames += (allNames.empty() ? "\"" : ", \"") + info.name + "\"";
        if (!wanted.empty() && lowercase(info.name).find(lowercase(wanted)) == std::string::npos)
            continue;
        anyNameMatched = true;
        if (const std::string reason = unsuitableReason(candidate); !reason.empty()) {
            rejections += (rejections.empty() ? "" : "; ") + info.name + " " + reason;
            continue;
        }
        if (typeRank(info.type) < bestRank) {
            best = candidate;
            bestRank = typeRank(info.type);
        }
    }
    if (!anyNameMatched)
        return Error{"no Vulkan device matches \"" + wanted + "\" (from " + wantedFrom +
                     "); devices are: " + allNames};
    if (best == VK_NULL_HANDLE) return Error{"no usable Vulkan device: " + rejections};

    ctx->physicalDevice_ = best;
    ctx->info_ = describe(best);
    vkGetPhysicalDeviceProperties(best, &ctx->properties_);
    vkGetPhysicalDeviceMemoryProperties(best, &ctx->memory_);

    // --- Features: query, then enable what the project uses when present ----------------------
    const std::vector<std::string> deviceExtensions = deviceExtensionNames(best);
    const bool hasTransformFeedback =
        contains(deviceExtensions, VK_EXT_TRANSFORM_FEEDBACK_EXTENSION_NAME);
    const bool hasAtomicFloat =
        contains(deviceExtensions, VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);

    FeatureChain supported;
    supported.link(hasTransformFeedback, hasAtomicFloat);
    vkGetPhysicalDeviceFeatures2(best, &supported.core);

    FeatureChain enabled;
    enabled.link(hasTransformFeedback, hasAtomicFloat);
    const VkPhysicalDeviceFeatures& have = supported.core.features;
    VkPhysicalDeviceFeatures& use = enabled.core.features;
    use.geometryShader = have.geometryShader;
    use.fillModeNonSolid = have.fillModeNonSolid;
    use.wideLines = have.wideLines;
    use.largePoints = have.largePoints;
    use.samplerAnisotropy = have.samplerAnisotropy;
    use.independentBlend = have.independentBlend;
    use.shaderInt16 = have.shaderInt16;
    use.shaderStorageImageReadWithoutFormat = have.shaderStorageImageReadWithoutFormat;
    use.shaderStorageImageWriteWithoutFormat = have.shaderStorageImageWriteWithoutFormat;
    use.shaderStorageImageExtendedFormats = have.shaderStorageImageExtendedFormats;
    use.vertexPipelineStoresAndAtomics = have.vertexPipelineStoresAndAtomics;
    use.fragmentStoresAndAtomics = have.fragmentStoresAndAtomics;
    use.pipelineStatisticsQuery = have.pipelineStatisticsQuery;
    enabled.v11.storageBuffer16BitAccess = supported.v11.storageBuffer16BitAccess;
    enabled.v11.uniformAndStorageBuffer16BitAccess =
        supported.v11.uniformAndStorageBuffer16BitAccess;
    enabled.v12.shaderFloat16 = supported.v12.shaderFloat16;
    enabled.v12.hostQueryReset = supported.v12.hostQueryReset;
    enabled.v12.scalarBlockLayout = supported.v12.scalarBlockLayout;
    enabled.v12.timelineSemaphore = supported.v12.timelineSemaphore;
    enabled.v13.dynamicRendering = VK_TRUE;
    enabled.v13.synchronization2 = VK_TRUE;
    enabled.v13.maintenance4 = supported.v13.maintenance4;
    if (hasTransformFeedback) {
        enabled.transformFeedback.transformFeedback = supported.transformFeedback.transformFeedback;
        enabled.transformFeedback.geometryStreams = supported.transformFeedback.geometryStreams;
    }
    if (hasAtomicFloat) {
        enabled.atomicFloat.shaderBufferFloat32Atomics =
            supported.atomicFloat.shaderBufferFloat32Atomics;
        enabled.atomicFloat.shaderBufferFloat32AtomicAdd =
            supported.atomicFloat.shaderBufferFloat32AtomicAdd;
        enabled.atomicFloat.shaderImageFloat32Atomics =
            supported.atomicFloat.shaderImageFloat32Atomics;
        enabled.atomicFloat.shaderImageFloat32AtomicAdd =
            supported.atomicFloat.shaderImageFloat32AtomicAdd;
    }

    const uint32_t family = universalQueueFamily(best);
    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(best, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(best, &familyCount, families.data());

    ctx->features_ = recordedFeatures(enabled, hasTransformFeedback, hasAtomicFloat,
                                      families[family], ctx->properties_.limits);

    // --- Logical device -------------------------------------------------------------------------
    std::vector<const char*> enabledExtensions = options.deviceExtensions;
    for (const char* name : enabledExtensions)
        if (!contains(deviceExtensions, name))
            return Error{ctx->info_.name + " lacks the device extension " + name};
    for (const char* name : requiredDeviceExtensions())
        enabledExtensions.push_back(name);
    if (hasTransformFeedback) enabledExtensions.push_back(VK_EXT_TRANSFORM_FEEDBACK_EXTENSION_NAME);
    if (hasAtomicFloat) enabledExtensions.push_back(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
    if (contains(deviceExtensions, "VK_KHR_portability_subset"))
        enabledExtensions.push_back("VK_KHR_portability_subset");

    const uint32_t queueCount = std::min(2u, families[family].queueCount);
    const float priorities[2] = {1.0f, 1.0f};
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = family;
    queueInfo.queueCount = queueCount;
    queueInfo.pQueuePriorities = priorities;

    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.pNext = &enabled.core;
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    deviceInfo.enabledExtensionCount = static_cast<uint32_t>(enabledExtensions.size());
    deviceInfo.ppEnabledExtensionNames = enabledExtensions.data();
    const VkResult deviceResult = vkCreateDevice(best, &deviceInfo, nullptr, &ctx->device_);
    if (deviceResult != VK_SUCCESS)
        return Error{"could not create a Vulkan device on " + ctx->info_.name + ": " +
                     toString(deviceResult)};

    ctx->graphicsQueue_.family = family;
    vkGetDeviceQueue(ctx->device_, family, 0, &ctx->graphicsQueue_.queue);
    vkGetDeviceQueue(ctx->device_, family, queueCount - 1, &ctx->computeQueue_.queue);
    ctx->computeQueue_.family = family;
    if (Status ready = ctx->finishDevice(); !ready) return ready.error();

    return Result<std::unique_ptr<Context>>(std::move(ctx));
}

Status Context::finishDevice() {
    pushDescriptorSet_ = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
        deviceFunction("vkCmdPushDescriptorSetKHR"));
    if (pushDescriptorSet_ == nullptr)
        return Error{info_.name + " offers no vkCmdPushDescriptorSetKHR"};
    VkPhysicalDevicePushDescriptorPropertiesKHR pushProperties{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PUSH_DESCRIPTOR_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties2.pNext = &pushProperties;
    vkGetPhysicalDeviceProperties2(physicalDevice_, &properties2);
    maxPushDescriptors_ = pushProperties.maxPushDescriptors;

    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags =
        VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = graphicsQueue_.family;
    VkCommandPool pool = VK_NULL_HANDLE;
    if (const VkResult made = vkCreateCommandPool(device_, &poolInfo, nullptr, &pool);
        made != VK_SUCCESS)
        return Error{std::string("could not create a command pool: ") + toString(made)};
    oneShotPool_ = UniqueCommandPool(device_, pool);
    return Ok{};
}

Result<std::unique_ptr<Context>> Context::adopt(const AdoptedDevice& host) {
    if (host.instance == VK_NULL_HANDLE || host.physicalDevice == VK_NULL_HANDLE ||
        host.device == VK_NULL_HANDLE || host.queue == VK_NULL_HANDLE)
        return Error{"the host's instance, physical device, device and queue must all be given"};
    if (host.enabledFeatures == nullptr ||
        host.enabledFeatures->sType != VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2)
        return Error{"the host's enabled features must be a VkPhysicalDeviceFeatures2 chain"};
    std::unique_ptr<Context> ctx(new Context());
    ctx->ownsDevice_ = false;
    ctx->instance_ = host.instance;
    ctx->physicalDevice_ = host.physicalDevice;
    ctx->device_ = host.device;
    ctx->info_ = describe(host.physicalDevice);
    vkGetPhysicalDeviceProperties(host.physicalDevice, &ctx->properties_);
    vkGetPhysicalDeviceMemoryProperties(host.physicalDevice, &ctx->memory_);

    // Everything that is missing, one a line.
    std::vector<std::string> missing;
    if (ctx->info_.apiVersion < kRequiredApiVersion)
        missing.push_back("Vulkan 1.3 (the device supports " +
                          versionString(ctx->info_.apiVersion) + ")");
    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(host.physicalDevice, &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(host.physicalDevice, &familyCount, families.data());
    const VkQueueFlags wanted = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    if (host.queueFamily >= familyCount)
        missing.push_back("queue family " + std::to_string(host.queueFamily) + " (the device has " +
                          std::to_string(familyCount) + ")");
    else if ((families[host.queueFamily].queueFlags & wanted) != wanted)
        missing.push_back("graphics and compute on queue family " +
                          std::to_string(host.queueFamily));
    const FeatureChain enabled = copiedChain(*host.enabledFeatures);
    const auto feature = [&](bool on, const char* name) {
        if (!on) missing.push_back(std::string("the feature ") + name);
    };
    feature(enabled.v13.dynamicRendering, "dynamicRendering (VkPhysicalDeviceVulkan13Features)");
    feature(enabled.v13.synchronization2, "synchronization2 (VkPhysicalDeviceVulkan13Features)");
    feature(enabled.core.features.geometryShader, "geometryShader (VkPhysicalDeviceFeatures)");
    const auto extension = [&](const char* name) { return contains(host.enabledExtensions, name); };
    for (const char* name : requiredDeviceExtensions())
        if (!extension(name)) missing.push_back(std::string("the device extension ") + name);
    if (!missing.empty()) {
        std::string text = ctx->info_.name + " was not created with what motionfx needs:";
        for (const std::string& line : missing)
            text += "\n  " + line;
        return Error{text};
    }

    ctx->graphicsQueue_ = {host.queue, host.queueFamily};
    ctx->computeQueue_ = ctx->graphicsQueue_;
    const bool transformFeedback = extension(VK_EXT_TRANSFORM_FEEDBACK_EXTENSION_NAME);
    const bool atomicFloat = extension(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
    ctx->features_ = recordedFeatures(enabled, transformFeedback, atomicFloat,
                                      families[host.queueFamily], ctx->properties_.limits);
    if (Status ready = ctx->finishDevice(); !ready) return ready.error();
    return Result<std::unique_ptr<Context>>(std::move(ctx));
}

std::span<const char* const> requiredDeviceExtensions() {
    static constexpr const char* kNames[] = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    return kNames;
}

std::shared_ptr<const ProgramObjects> Context::findProgram(const std::string& key) const {
    std::lock_guard<std::mutex> lock(programsMutex_);
    const auto it = programs_.find(key);
    return it == programs_.end() ? nullptr : it->second;
}

void Context::keepProgram(const std::string& key,
                          std::shared_ptr<const ProgramObjects> objects) const {
    std::lock_guard<std::mutex> lock(programsMutex_);
    programs_.emplace(key, std::move(objects));
}

Context::~Context() {
    if (device_ != VK_NULL_HANDLE) {
        // An adopted device is the host's: only its queue is ours to wait for.
        if (ownsDevice_)
            vkDeviceWaitIdle(device_);
        else if (graphicsQueue_.queue != VK_NULL_HANDLE)
            vkQueueWaitIdle(graphicsQueue_.queue);
        programs_.clear(); // their pipelines and layouts, before the device
        oneShotPool_.reset();
        if (!ownsDevice_) return; // the host's device and instance stay
        vkDestroyDevice(device_, nullptr);
    }
    if (messenger_ != VK_NULL_HANDLE) {
        auto destroyMessenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroyMessenger != nullptr) destroyMessenger(instance_, messenger_, nullptr);
    }
    if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::debugCallback(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT /*types*/,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* ctx = static_cast<Context*>(user);
    const bool isError = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0;
    const std::string text = data->pMessage != nullptr ? data->pMessage : "(no message)";
    if (ctx->printValidation_)
        std::fprintf(stderr, "vulkan %s: %s\n", isError ? "error" : "warning", text.c_str());
    {
        std::lock_guard lock(ctx->messagesMutex_);
        ctx->messages_.push_back(
            {isError ? MessageSeverity::Error : MessageSeverity::Warning, text});
    }
    return VK_FALSE; // never abort the call; the test fixture decides
}

std::vector<ValidationMessage> Context::validationMessages() const {
    std::lock_guard lock(messagesMutex_);
    return messages_;
}

size_t Context::validationErrorCount() const {
    std::lock_guard lock(messagesMutex_);
    return static_cast<size_t>(
        std::count_if(messages_.begin(), messages_.end(), [](const ValidationMessage& m) {
            return m.severity == MessageSeverity::Error;
        }));
}

void Context::clearValidationMessages() {
    std::lock_guard lock(messagesMutex_);
    messages_.clear();
}

uint32_t Context::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                                 VkMemoryPropertyFlags preferred) const {
    uint32_t fallback = UINT32_MAX;
    for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
        if ((typeBits & (1u << i)) == 0) continue;
        const VkMemoryPropertyFlags flags = memory_.memoryTypes[i].propertyFlags;
        if ((flags & required) != required) continue;
        if ((flags & preferred) == preferred) return i;
        if (fallback == UINT32_MAX) fallback = i;
    }
    return fallback;
}

// Asked of the Vulkan loader itself when the plain call gives nothing: a library loaded ahead of it
// (LD_PRELOAD of a layer, as the sanitizer runs do) can shadow the loader's exported
// vkGetDeviceProcAddr with one that does not know this device.
PFN_vkVoidFunction Context::deviceFunction(const char* name) const {
    if (PFN_vkVoidFunction f = vkGetDeviceProcAddr(device_, name)) return f;
    void* loader = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_NOLOAD);
    if (!loader) return nullptr;
    auto get = reinterpret_cast<PFN_vkGetDeviceProcAddr>(dlsym(loader, "vkGetDeviceProcAddr"));
    PFN_vkVoidFunction f = get ? get(device_, name) : nullptr;
    dlclose(loader);
    return f;
}

void Context::setDebugName(VkObjectType type, uint64_t handle, const char* name) const {
    if (setObjectName_ == nullptr || name == nullptr || handle == 0) return;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name;
    setObjectName_(device_, &info);
}

std::vector<DeviceInfo> Context::listDevices() const {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance_, &count, devices.data());
    std::vector<DeviceInfo> infos;
    for (VkPhysicalDevice d : devices)
        infos.push_back(describe(d));
    return infos;
}

void Context::waitIdle() const {
    MFX_VK_CHECK(vkDeviceWaitIdle(device_));
}

} // namespace mfx::gpu
