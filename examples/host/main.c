/* A host application that embeds motionfx (docs/embedding.md): it makes its own Vulkan instance
 * and device, as an engine does, enabling what motionfx asks for, and hands them to a motionfx
 * runtime, then makes the effects of a scene file on it. Headless: no window, no surface.
 *
 *   motionfx_host [--headless] [--scene FILE]
 */
#include <motionfx/motionfx.h>

#include <stdio.h>
#include <string.h>

/* The host's device: the first with a queue family that has graphics and compute. */
typedef struct Host {
    VkInstance instance;
    VkPhysicalDevice physicalDevice;
    uint32_t family;
    VkDevice device;
    VkQueue queue;
    VkPhysicalDeviceFeatures2 features;
    VkPhysicalDeviceVulkan11Features v11;
    VkPhysicalDeviceVulkan12Features v12;
    VkPhysicalDeviceVulkan13Features v13;
    const char* extensions[8];
    uint32_t extensionCount;
} Host;

static int makeHost(Host* host) {
    VkApplicationInfo app;
    VkInstanceCreateInfo instanceInfo;
    VkPhysicalDevice devices[16];
    uint32_t deviceCount = 16, d;
    VkDeviceQueueCreateInfo queueInfo;
    VkDeviceCreateInfo deviceInfo;
    const float priority = 1.0f;

    memset(host, 0, sizeof *host);
    memset(&app, 0, sizeof app);
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "motionfx host example";
    app.apiVersion = VK_API_VERSION_1_3;
    memset(&instanceInfo, 0, sizeof instanceInfo);
    instanceInfo.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    instanceInfo.pApplicationInfo = &app;
    if (vkCreateInstance(&instanceInfo, NULL, &host->instance) != VK_SUCCESS) {
        fprintf(stderr, "motionfx_host: no Vulkan 1.3 instance\n");
        return 0;
    }
    if (vkEnumeratePhysicalDevices(host->instance, &deviceCount, devices) < 0) deviceCount = 0;
    for (d = 0; d < deviceCount && host->physicalDevice == VK_NULL_HANDLE; ++d) {
        VkQueueFamilyProperties families[16];
        uint32_t familyCount = 16, f;
        vkGetPhysicalDeviceQueueFamilyProperties(devices[d], &familyCount, families);
        for (f = 0; f < familyCount; ++f)
            if ((families[f].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
                (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
                host->physicalDevice = devices[d];
                host->family = f;
                break;
            }
    }
    if (host->physicalDevice == VK_NULL_HANDLE) {
        fprintf(stderr, "motionfx_host: no device with a graphics and compute queue\n");
        return 0;
    }

    /* What motionfx needs (docs/embedding.md), beside what the host itself uses. */
    host->features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    host->v11.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES;
    host->v12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
    host->v13.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES;
    host->features.pNext = &host->v11;
    host->v11.pNext = &host->v12;
    host->v12.pNext = &host->v13;
    host->features.features.geometryShader = VK_TRUE;
    host->v13.dynamicRendering = VK_TRUE;
    host->v13.synchronization2 = VK_TRUE;
    host->extensionCount = mfxRequiredDeviceExtensions(host->extensions, 8);
    if (host->extensionCount > 8) {
        fprintf(stderr, "motionfx_host: motionfx asks for more extensions than this host holds\n");
        return 0;
    }

    memset(&queueInfo, 0, sizeof queueInfo);
    queueInfo.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    queueInfo.queueFamilyIndex = host->family;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    memset(&deviceInfo, 0, sizeof deviceInfo);
    deviceInfo.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    deviceInfo.pNext = &host->features;
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    deviceInfo.enabledExtensionCount = host->extensionCount;
    deviceInfo.ppEnabledExtensionNames = host->extensions;
    if (vkCreateDevice(host->physicalDevice, &deviceInfo, NULL, &host->device) != VK_SUCCESS) {
        fprintf(stderr, "motionfx_host: could not create the device (does it have "
                        "geometryShader, dynamicRendering, synchronization2 and %s?)\n",
                host->extensionCount > 0 ? host->extensions[0] : "");
        return 0;
    }
    vkGetDeviceQueue(host->device, host->family, 0, &host->queue);
    return 1;
}

static void destroyHost(Host* host) {
    if (host->device != VK_NULL_HANDLE) vkDestroyDevice(host->device, NULL);
    if (host->instance != VK_NULL_HANDLE) vkDestroyInstance(host->instance, NULL);
}

static void printMessage(MfxResult result, const char* message, void* user) {
    (void)user;
    fprintf(stderr, "motionfx_host: %s: %s\n", mfxResultName(result), message);
}

int main(int argc, char** argv) {
    Host host;
    MfxRuntimeDesc desc;
    MfxRuntime runtime = NULL;
    const char* sceneFile = NULL;
    uint32_t version;
    int i;

    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--headless") == 0) continue;
        if (strcmp(argv[i], "--scene") == 0 && i + 1 < argc) {
            sceneFile = argv[++i];
            continue;
        }
        fprintf(stderr, "motionfx_host: unknown argument \"%s\"; usage: motionfx_host "
                        "[--headless] [--scene FILE]\n", argv[i]);
        return 2;
    }
    if (!makeHost(&host)) {
        destroyHost(&host);
        return 1;
    }

    memset(&desc, 0, sizeof desc);
    desc.structVersion = MFX_RUNTIME_DESC_VERSION;
    desc.instance = host.instance;
    desc.physicalDevice = host.physicalDevice;
    desc.device = host.device;
    desc.queueFamilyIndex = host.family;
    desc.queue = host.queue;
    desc.enabledFeatures = &host.features;
    desc.enabledExtensionCount = host.extensionCount;
    desc.enabledExtensionNames = host.extensions;
    desc.messageCallback = printMessage;
    if (mfxCreateRuntime(&desc, &runtime) != MFX_SUCCESS) {
        destroyHost(&host);
        return 1;
    }
    version = mfxVersion();
    printf("motionfx %u.%u.%u runtime on %s\n", version / 10000, version / 100 % 100,
           version % 100, mfxRuntimeDeviceName(runtime));

    if (sceneFile != NULL) {
        MfxEffectsDesc effectsDesc;
        MfxEffects effects = NULL;
        MfxEffectsInfo info;
        uint32_t e;
        memset(&effectsDesc, 0, sizeof effectsDesc);
        memset(&info, 0, sizeof info);
        info.structVersion = MFX_EFFECTS_INFO_VERSION;
        effectsDesc.structVersion = MFX_EFFECTS_DESC_VERSION;
        effectsDesc.sceneFile = sceneFile;
        if (mfxCreateEffects(runtime, &effectsDesc, &effects) != MFX_SUCCESS ||
            mfxGetEffectsInfo(effects, &info) != MFX_SUCCESS) {
            mfxDestroyEffects(effects);
            mfxDestroyRuntime(runtime);
            destroyHost(&host);
            return 1;
        }
        printf("%s: %u effects, %u smoke grids, %u frames at %g fps\n", sceneFile,
               info.effectCount, info.smokeGrids, info.frameCount, (double)info.framesPerSecond);
        for (e = 0; e < info.effectCount; ++e)
            printf("  %s\n", mfxEffectName(effects, e));
        mfxDestroyEffects(effects);
    }

    mfxDestroyRuntime(runtime);
    destroyHost(&host);
    return 0;
}
