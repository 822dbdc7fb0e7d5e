/* A host application that embeds motionfx (docs/embedding.md), as an engine would: it makes its
 * own Vulkan instance and device, enabling what motionfx asks for, draws its own floor and its own
 * character with its own shaders into its own colour and depth images, and has motionfx add the
 * scene's effects (speed-lines, trails, smoke) into that frame, depth-faded against its surfaces.
 * Headless: no window, no surface; frames can be written as PPM pictures.
 *
 *   motionfx_host [--headless] [--scene FILE] [--frames N] [--size WxH] [--depth FORMAT]
 *                 [--save FRAME --out DIR] [--black] [--host-animation] [--validate]
 *
 * --frames N     draw N frames (default: the scene's clip; 0 makes the effects only)
 * --size WxH     the frame's size (default 640x360)
 * --depth F      the host's depth format: d16, d24s8, d32 (default) or d32s8
 * --save FRAME   write frame FRAME as DIR/frame_FRAME.ppm, and the host's own picture before
 *                motionfx drew into it as DIR/under_FRAME.ppm
 * --black        draw the sky, the floor and the character black (their depth as always): the
 *                frame is then the effects' own premultiplied colour, for comparisons
 * --host-animation
 *                give motionfx the character's node matrices each frame, as a host with its own
 *                animation system does (here the scene clip's, read from motionfx)
 * --validate     run under the Vulkan validation layer; any error or warning it reports fails
 */
#include <motionfx/motionfx.h>

#include "host_frag.h" /* the host's own shaders, compiled by this project's build */
#include "host_vert.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define COLOUR_FORMAT VK_FORMAT_R8G8B8A8_SRGB

/* --- The host's device ----------------------------------------------------------------------- */

typedef struct Host {
    VkInstance instance;
    VkDebugUtilsMessengerEXT messenger;
    unsigned validationMessages;
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

static VKAPI_ATTR VkBool32 VKAPI_CALL onValidation(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT types,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user) {
    Host* host = (Host*)user;
    (void)severity;
    (void)types;
    ++host->validationMessages;
    fprintf(stderr, "motionfx_host: validation: %s\n", data->pMessage);
    return VK_FALSE;
}

static int hasLayer(const char* name) {
    VkLayerProperties layers[64];
    uint32_t count = 64, i;
    if (vkEnumerateInstanceLayerProperties(&count, layers) < 0) return 0;
    for (i = 0; i < count; ++i)
        if (strcmp(layers[i].layerName, name) == 0) return 1;
    return 0;
}

static int makeHost(Host* host, int validate) {
    static const char* const validation = "VK_LAYER_KHRONOS_validation";
    static const char* const debugUtils = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkApplicationInfo app;
    VkInstanceCreateInfo instanceInfo;
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo;
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
    memset(&messengerInfo, 0, sizeof messengerInfo);
    messengerInfo.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                    VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
    messengerInfo.pfnUserCallback = onValidation;
    messengerInfo.pUserData = host;
    if (validate) {
        if (!hasLayer(validation)) {
            fprintf(stderr, "motionfx_host: --validate: %s is not installed\n", validation);
            return 0;
        }
        instanceInfo.enabledLayerCount = 1;
        instanceInfo.ppEnabledLayerNames = &validation;
        instanceInfo.enabledExtensionCount = 1;
        instanceInfo.ppEnabledExtensionNames = &debugUtils;
    }
    if (vkCreateInstance(&instanceInfo, NULL, &host->instance) != VK_SUCCESS) {
        fprintf(stderr, "motionfx_host: no Vulkan 1.3 instance\n");
        return 0;
    }
    if (validate) {
        PFN_vkCreateDebugUtilsMessengerEXT create =
            (PFN_vkCreateDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
                host->instance, "vkCreateDebugUtilsMessengerEXT");
        if (create == NULL ||
            create(host->instance, &messengerInfo, NULL, &host->messenger) != VK_SUCCESS) {
            fprintf(stderr, "motionfx_host: --validate: no debug messenger\n");
            return 0;
        }
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
        fprintf(stderr,
                "motionfx_host: could not create the device (does it have "
                "geometryShader, dynamicRendering, synchronization2 and %s?)\n",
                host->extensionCount > 0 ? host->extensions[0] : "");
        return 0;
    }
    vkGetDeviceQueue(host->device, host->family, 0, &host->queue);
    return 1;
}

static void destroyHost(Host* host) {
    if (host->device != VK_NULL_HANDLE) vkDestroyDevice(host->device, NULL);
    if (host->messenger != VK_NULL_HANDLE) {
        PFN_vkDestroyDebugUtilsMessengerEXT destroy =
            (PFN_vkDestroyDebugUtilsMessengerEXT)vkGetInstanceProcAddr(
                host->instance, "vkDestroyDebugUtilsMessengerEXT");
        if (destroy != NULL) destroy(host->instance, host->messenger, NULL);
    }
    if (host->instance != VK_NULL_HANDLE) vkDestroyInstance(host->instance, NULL);
}

/* --- The host's own resources ---------------------------------------------------------------- */

typedef struct Buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void* mapped;
} Buffer;

typedef struct Image {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
} Image;

static int memoryType(const Host* host, uint32_t bits, VkMemoryPropertyFlags wanted) {
    VkPhysicalDeviceMemoryProperties properties;
    uint32_t i;
    vkGetPhysicalDeviceMemoryProperties(host->physicalDevice, &properties);
    for (i = 0; i < properties.memoryTypeCount; ++i)
        if ((bits & (1u << i)) && (properties.memoryTypes[i].propertyFlags & wanted) == wanted)
            return (int)i;
    return -1;
}

/* Memory of a type with the `wanted` properties for `needs`, into `memory`. */
static int allocate(const Host* host, const VkMemoryRequirements* needs,
                    VkMemoryPropertyFlags wanted, VkDeviceMemory* memory) {
    VkMemoryAllocateInfo allocation;
    const int type = memoryType(host, needs->memoryTypeBits, wanted);
    if (type < 0) return 0;
    memset(&allocation, 0, sizeof allocation);
    allocation.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    allocation.allocationSize = needs->size;
    allocation.memoryTypeIndex = (uint32_t)type;
    return vkAllocateMemory(host->device, &allocation, NULL, memory) == VK_SUCCESS;
}

/* A host-visible, mapped buffer. */
static int makeBuffer(const Host* host, VkDeviceSize size, VkBufferUsageFlags usage, Buffer* out) {
    VkBufferCreateInfo info;
    VkMemoryRequirements needs;
    memset(out, 0, sizeof *out);
    memset(&info, 0, sizeof info);
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = size;
    info.usage = usage;
    if (vkCreateBuffer(host->device, &info, NULL, &out->buffer) != VK_SUCCESS) return 0;
    vkGetBufferMemoryRequirements(host->device, out->buffer, &needs);
    if (!allocate(host, &needs,
                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                  &out->memory))
        return 0;
    if (vkBindBufferMemory(host->device, out->buffer, out->memory, 0) != VK_SUCCESS) return 0;
    return vkMapMemory(host->device, out->memory, 0, VK_WHOLE_SIZE, 0, &out->mapped) == VK_SUCCESS;
}

static void destroyBuffer(const Host* host, Buffer* buffer) {
    if (buffer->buffer != VK_NULL_HANDLE) vkDestroyBuffer(host->device, buffer->buffer, NULL);
    if (buffer->memory != VK_NULL_HANDLE) vkFreeMemory(host->device, buffer->memory, NULL);
}

static int makeImage(const Host* host, uint32_t width, uint32_t height, VkFormat format,
                     VkImageUsageFlags usage, VkImageAspectFlags aspect, Image* out) {
    VkImageCreateInfo info;
    VkMemoryRequirements needs;
    VkImageViewCreateInfo viewInfo;
    memset(out, 0, sizeof *out);
    memset(&info, 0, sizeof info);
    info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent.width = width;
    info.extent.height = height;
    info.extent.depth = 1;
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    if (vkCreateImage(host->device, &info, NULL, &out->image) != VK_SUCCESS) return 0;
    vkGetImageMemoryRequirements(host->device, out->image, &needs);
    if (!allocate(host, &needs, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &out->memory)) return 0;
    if (vkBindImageMemory(host->device, out->image, out->memory, 0) != VK_SUCCESS) return 0;
    memset(&viewInfo, 0, sizeof viewInfo);
    viewInfo.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    viewInfo.image = out->image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format;
    viewInfo.subresourceRange.aspectMask = aspect;
    viewInfo.subresourceRange.levelCount = 1;
    viewInfo.subresourceRange.layerCount = 1;
    return vkCreateImageView(host->device, &viewInfo, NULL, &out->view) == VK_SUCCESS;
}

static void destroyImage(const Host* host, Image* image) {
    if (image->view != VK_NULL_HANDLE) vkDestroyImageView(host->device, image->view, NULL);
    if (image->image != VK_NULL_HANDLE) vkDestroyImage(host->device, image->image, NULL);
    if (image->memory != VK_NULL_HANDLE) vkFreeMemory(host->device, image->memory, NULL);
}

static void barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect,
                    VkImageLayout from, VkImageLayout to) {
    VkImageMemoryBarrier2 b;
    VkDependencyInfo dependency;
    memset(&b, 0, sizeof b);
    b.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2;
    b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange.aspectMask = aspect;
    b.subresourceRange.levelCount = 1;
    b.subresourceRange.layerCount = 1;
    memset(&dependency, 0, sizeof dependency);
    dependency.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO;
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dependency);
}

/* The host's one pipeline: lit, flat-coloured triangles (host.vert, host.frag). */
typedef struct Draw {
    float viewProjection[16];
    float colour[4];
} Draw;

static int makePipeline(const Host* host, VkFormat depthFormat, VkPipelineLayout* layout,
                        VkPipeline* pipeline) {
    VkPushConstantRange range;
    VkPipelineLayoutCreateInfo layoutInfo;
    VkShaderModuleCreateInfo moduleInfo;
    VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
    VkPipelineShaderStageCreateInfo stages[2];
    VkVertexInputBindingDescription bindings[2];
    VkVertexInputAttributeDescription attributes[2];
    VkPipelineVertexInputStateCreateInfo vertexInput;
    VkPipelineInputAssemblyStateCreateInfo assembly;
    VkPipelineViewportStateCreateInfo viewport;
    VkPipelineRasterizationStateCreateInfo raster;
    VkPipelineMultisampleStateCreateInfo multisample;
    VkPipelineDepthStencilStateCreateInfo depth;
    VkPipelineColorBlendAttachmentState blendAttachment;
    VkPipelineColorBlendStateCreateInfo blend;
    const VkDynamicState dynamics[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic;
    const VkFormat colourFormat = COLOUR_FORMAT;
    VkPipelineRenderingCreateInfo rendering;
    VkGraphicsPipelineCreateInfo info;
    int ok;

    memset(&range, 0, sizeof range);
    range.stageFlags = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    range.size = sizeof(Draw);
    memset(&layoutInfo, 0, sizeof layoutInfo);
    layoutInfo.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &range;
    if (vkCreatePipelineLayout(host->device, &layoutInfo, NULL, layout) != VK_SUCCESS) return 0;

    memset(&moduleInfo, 0, sizeof moduleInfo);
    moduleInfo.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    moduleInfo.codeSize = sizeof host_vert;
    moduleInfo.pCode = host_vert;
    if (vkCreateShaderModule(host->device, &moduleInfo, NULL, &vert) != VK_SUCCESS) return 0;
    moduleInfo.codeSize = sizeof host_frag;
    moduleInfo.pCode = host_frag;
    if (vkCreateShaderModule(host->device, &moduleInfo, NULL, &frag) != VK_SUCCESS) {
        vkDestroyShaderModule(host->device, vert, NULL);
        return 0;
    }
    memset(stages, 0, sizeof stages);
    stages[0].sType = stages[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vert;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = frag;
    stages[1].pName = "main";

    /* Positions and normals in buffers of their own, 3 floats a vertex. */
    memset(bindings, 0, sizeof bindings);
    memset(attributes, 0, sizeof attributes);
    bindings[0].binding = 0;
    bindings[0].stride = 3 * sizeof(float);
    bindings[1].binding = 1;
    bindings[1].stride = 3 * sizeof(float);
    attributes[0].location = 0;
    attributes[0].binding = 0;
    attributes[0].format = VK_FORMAT_R32G32B32_SFLOAT;
    attributes[1].location = 1;
    attributes[1].binding = 1;
    attributes[1].format = VK_FORMAT_R32G32B32_SFLOAT;
    memset(&vertexInput, 0, sizeof vertexInput);
    vertexInput.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    vertexInput.vertexBindingDescriptionCount = 2;
    vertexInput.pVertexBindingDescriptions = bindings;
    vertexInput.vertexAttributeDescriptionCount = 2;
    vertexInput.pVertexAttributeDescriptions = attributes;
    memset(&assembly, 0, sizeof assembly);
    assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    memset(&viewport, 0, sizeof viewport);
    viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    memset(&raster, 0, sizeof raster);
    raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_NONE;
    raster.lineWidth = 1.0f;
    memset(&multisample, 0, sizeof multisample);
    multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    memset(&depth, 0, sizeof depth);
    depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
    depth.depthTestEnable = VK_TRUE;
    depth.depthWriteEnable = VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_LESS;
    memset(&blendAttachment, 0, sizeof blendAttachment);
    blendAttachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                     VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    memset(&blend, 0, sizeof blend);
    blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    blend.attachmentCount = 1;
    blend.pAttachments = &blendAttachment;
    memset(&dynamic, 0, sizeof dynamic);
    dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamics;
    memset(&rendering, 0, sizeof rendering);
    rendering.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &colourFormat;
    rendering.depthAttachmentFormat = depthFormat;
    if (depthFormat == VK_FORMAT_D24_UNORM_S8_UINT || depthFormat == VK_FORMAT_D32_SFLOAT_S8_UINT)
        rendering.stencilAttachmentFormat = depthFormat;
    memset(&info, 0, sizeof info);
    info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    info.pNext = &rendering;
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = *layout;
    ok = vkCreateGraphicsPipelines(host->device, VK_NULL_HANDLE, 1, &info, NULL, pipeline) ==
         VK_SUCCESS;
    vkDestroyShaderModule(host->device, vert, NULL);
    vkDestroyShaderModule(host->device, frag, NULL);
    return ok;
}

/* out = a * b, column-major 4x4. */
static void multiply(const float* a, const float* b, float* out) {
    int c, r, k;
    for (c = 0; c < 4; ++c)
        for (r = 0; r < 4; ++r) {
            float sum = 0.0f;
            for (k = 0; k < 4; ++k)
                sum += a[k * 4 + r] * b[c * 4 + k];
            out[c * 4 + r] = sum;
        }
}

/* RGBA8 rows (as the colour image stores them, sRGB-encoded) to a binary PPM. */
static int writePpm(const char* path, const unsigned char* rgba, uint32_t width, uint32_t height) {
    FILE* file = fopen(path, "wb");
    size_t p;
    int ok;
    if (file == NULL) {
        fprintf(stderr, "motionfx_host: cannot write %s\n", path);
        return 0;
    }
    fprintf(file, "P6\n%u %u\n255\n", width, height);
    for (p = 0; p < (size_t)width * height; ++p)
        fwrite(rgba + 4 * p, 1, 3, file);
    ok = ferror(file) == 0;
    ok = fclose(file) == 0 && ok;
    if (!ok) fprintf(stderr, "motionfx_host: cannot write %s\n", path);
    return ok;
}

static void printMessage(MfxResult result, const char* message, void* user) {
    (void)user;
    fprintf(stderr, "motionfx_host: %s: %s\n", mfxResultName(result), message);
}

/* --- Options --------------------------------------------------------------------------------- */

typedef struct Options {
    const char* sceneFile;
    long frames; /* -1: the scene's clip */
    uint32_t width, height;
    VkFormat depthFormat;
    long save; /* -1: none */
    const char* out;
    int black;
    int hostAnimation;
    int validate;
} Options;

static int parseCount(const char* text, long largest, long* out) {
    char* end = NULL;
    long value = strtol(text, &end, 10);
    if (end == text || *end != '\0' || value < 0 || value > largest) return 0;
    *out = value;
    return 1;
}

static int parseOptions(int argc, char** argv, Options* options) {
    int i;
    memset(options, 0, sizeof *options);
    options->frames = -1;
    options->width = 640;
    options->height = 360;
    options->depthFormat = VK_FORMAT_D32_SFLOAT;
    options->save = -1;
    for (i = 1; i < argc; ++i) {
        const char* a = argv[i];
        const char* value = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--headless") == 0) continue;
        if (strcmp(a, "--validate") == 0) {
            options->validate = 1;
            continue;
        }
        if (strcmp(a, "--black") == 0) {
            options->black = 1;
            continue;
        }
        if (strcmp(a, "--host-animation") == 0) {
            options->hostAnimation = 1;
            continue;
        }
        if (value == NULL) {
            fprintf(stderr, "motionfx_host: %s needs a value\n", a);
            return 0;
        }
        ++i;
        if (strcmp(a, "--scene") == 0) {
            options->sceneFile = value;
        } else if (strcmp(a, "--out") == 0) {
            options->out = value;
        } else if (strcmp(a, "--frames") == 0) {
            if (!parseCount(value, 100000, &options->frames)) {
                fprintf(stderr, "motionfx_host: --frames: expected 0 to 100000, got \"%s\"\n",
                        value);
                return 0;
            }
        } else if (strcmp(a, "--save") == 0) {
            if (!parseCount(value, 100000, &options->save)) {
                fprintf(stderr, "motionfx_host: --save: expected a frame number, got \"%s\"\n",
                        value);
                return 0;
            }
        } else if (strcmp(a, "--size") == 0) {
            unsigned w = 0, h = 0;
            char tail = 0;
            if (sscanf(value, "%ux%u%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 8192 ||
                h > 8192) {
                fprintf(stderr, "motionfx_host: --size: expected WxH, each 1 to 8192, got \"%s\"\n",
                        value);
                return 0;
            }
            options->width = w;
            options->height = h;
        } else if (strcmp(a, "--depth") == 0) {
            if (strcmp(value, "d16") == 0)
                options->depthFormat = VK_FORMAT_D16_UNORM;
            else if (strcmp(value, "d24s8") == 0)
                options->depthFormat = VK_FORMAT_D24_UNORM_S8_UINT;
            else if (strcmp(value, "d32") == 0)
                options->depthFormat = VK_FORMAT_D32_SFLOAT;
            else if (strcmp(value, "d32s8") == 0)
                options->depthFormat = VK_FORMAT_D32_SFLOAT_S8_UINT;
            else if (strcmp(value, "rgba8") == 0) /* not a depth format: motionfx refuses it */
                options->depthFormat = VK_FORMAT_R8G8B8A8_UNORM;
            else {
                fprintf(stderr,
                        "motionfx_host: --depth: expected d16, d24s8, d32 or d32s8, got "
                        "\"%s\"\n",
                        value);
                return 0;
            }
        } else {
            fprintf(stderr,
                    "motionfx_host: unknown option \"%s\"; usage: motionfx_host "
                    "[--headless] [--scene FILE] [--frames N] [--size WxH] [--depth F] "
                    "[--save FRAME --out DIR] [--black] [--host-animation] [--validate]\n",
                    a);
            return 0;
        }
    }
    if ((options->save >= 0) != (options->out != NULL)) {
        fprintf(stderr, "motionfx_host: --save and --out go together\n");
        return 0;
    }
    return 1;
}

/* --- The frames ------------------------------------------------------------------------------ */

typedef struct Scene {
    MfxEffects effects;
    MfxEffectsInfo info;
    uint32_t vertexCount, indexCount;
    Buffer positions, normals, indices; /* the character, rewritten each frame */
    Buffer floorPositions, floorNormals;
    Image colour, depth;
    Buffer readback, readbackUnder;
    float* nodeMatrices; /* with --host-animation: 16 floats a character node */
    uint32_t nodeCount;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    VkFence fence;
} Scene;

static void destroyScene(const Host* host, Scene* s) {
    if (host->device != VK_NULL_HANDLE) vkDeviceWaitIdle(host->device);
    mfxDestroyEffects(s->effects);
    free(s->nodeMatrices);
    destroyBuffer(host, &s->positions);
    destroyBuffer(host, &s->normals);
    destroyBuffer(host, &s->indices);
    destroyBuffer(host, &s->floorPositions);
    destroyBuffer(host, &s->floorNormals);
    destroyBuffer(host, &s->readback);
    destroyBuffer(host, &s->readbackUnder);
    destroyImage(host, &s->colour);
    destroyImage(host, &s->depth);
    if (s->pipeline != VK_NULL_HANDLE) vkDestroyPipeline(host->device, s->pipeline, NULL);
    if (s->layout != VK_NULL_HANDLE) vkDestroyPipelineLayout(host->device, s->layout, NULL);
    if (s->fence != VK_NULL_HANDLE) vkDestroyFence(host->device, s->fence, NULL);
    if (s->pool != VK_NULL_HANDLE) vkDestroyCommandPool(host->device, s->pool, NULL);
}

static int makeScene(const Host* host, MfxRuntime runtime, const Options* o, Scene* s) {
    MfxEffectsDesc effectsDesc;
    VkCommandPoolCreateInfo poolInfo;
    VkCommandBufferAllocateInfo cmdInfo;
    VkFenceCreateInfo fenceInfo;
    const VkImageAspectFlags depthAspect = o->depthFormat == VK_FORMAT_R8G8B8A8_UNORM
                                               ? VK_IMAGE_ASPECT_COLOR_BIT
                                               : VK_IMAGE_ASPECT_DEPTH_BIT;
    const VkDeviceSize pixels = (VkDeviceSize)o->width * o->height;
    float* p;
    float* n;
    int i;

    memset(&effectsDesc, 0, sizeof effectsDesc);
    effectsDesc.structVersion = MFX_EFFECTS_DESC_VERSION;
    effectsDesc.sceneFile = o->sceneFile;
    s->info.structVersion = MFX_EFFECTS_INFO_VERSION;
    if (mfxCreateEffects(runtime, &effectsDesc, &s->effects) != MFX_SUCCESS ||
        mfxGetEffectsInfo(s->effects, &s->info) != MFX_SUCCESS ||
        mfxGetCharacterMeshSize(s->effects, &s->vertexCount, &s->indexCount) != MFX_SUCCESS)
        return 0;
    s->nodeCount = mfxGetCharacterNodeCount(s->effects);
    s->nodeMatrices = (float*)calloc(16u * s->nodeCount + 16u, sizeof(float));
    if (s->nodeMatrices == NULL) {
        fprintf(stderr, "motionfx_host: out of memory for the node matrices\n");
        return 0;
    }
    if (!makeBuffer(host, 12u * s->vertexCount + 12, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                    &s->positions) ||
        !makeBuffer(host, 12u * s->vertexCount + 12, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                    &s->normals) ||
        !makeBuffer(host, 4u * s->indexCount + 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, &s->indices) ||
        !makeBuffer(host, 6 * 12, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, &s->floorPositions) ||
        !makeBuffer(host, 6 * 12, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, &s->floorNormals) ||
        !makeBuffer(host, 4 * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT, &s->readback) ||
        !makeBuffer(host, 4 * pixels, VK_BUFFER_USAGE_TRANSFER_DST_BIT, &s->readbackUnder)) {
        fprintf(stderr, "motionfx_host: out of memory for the host's buffers\n");
        return 0;
    }
    if (mfxGetCharacterMesh(s->effects, 0.0, NULL, NULL, (uint32_t*)s->indices.mapped) !=
        MFX_SUCCESS)
        return 0;
    /* The host's floor: a square 40 units across at the stage's floor height. */
    p = (float*)s->floorPositions.mapped;
    n = (float*)s->floorNormals.mapped;
    for (i = 0; i < 6; ++i) {
        static const float corners[6][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, -1}, {1, 1}, {-1, 1}};
        p[3 * i + 0] = 20.0f * corners[i][0];
        p[3 * i + 1] = s->info.floorHeight;
        p[3 * i + 2] = 20.0f * corners[i][1];
        n[3 * i + 0] = 0.0f;
        n[3 * i + 1] = 1.0f;
        n[3 * i + 2] = 0.0f;
    }
    if (!makeImage(host, o->width, o->height, COLOUR_FORMAT,
                   VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                   VK_IMAGE_ASPECT_COLOR_BIT, &s->colour) ||
        !makeImage(host, o->width, o->height, o->depthFormat,
                   (depthAspect == VK_IMAGE_ASPECT_DEPTH_BIT
                        ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                        : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) |
                       VK_IMAGE_USAGE_SAMPLED_BIT,
                   depthAspect, &s->depth)) {
        fprintf(stderr, "motionfx_host: could not make the %ux%u colour and depth images\n",
                o->width, o->height);
        return 0;
    }
    if (depthAspect == VK_IMAGE_ASPECT_DEPTH_BIT &&
        !makePipeline(host, o->depthFormat, &s->layout, &s->pipeline)) {
        fprintf(stderr, "motionfx_host: could not make the host's pipeline\n");
        return 0;
    }
    memset(&poolInfo, 0, sizeof poolInfo);
    poolInfo.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = host->family;
    memset(&cmdInfo, 0, sizeof cmdInfo);
    cmdInfo.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    cmdInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cmdInfo.commandBufferCount = 1;
    memset(&fenceInfo, 0, sizeof fenceInfo);
    fenceInfo.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    if (vkCreateCommandPool(host->device, &poolInfo, NULL, &s->pool) != VK_SUCCESS) return 0;
    cmdInfo.commandPool = s->pool;
    if (vkAllocateCommandBuffers(host->device, &cmdInfo, &s->cmd) != VK_SUCCESS ||
        vkCreateFence(host->device, &fenceInfo, NULL, &s->fence) != VK_SUCCESS)
        return 0;
    return 1;
}

/* The host's own drawing: its floor and its character, lit by one light, into its colour and
 * depth; the images end in COLOR_ATTACHMENT_OPTIMAL and DEPTH_ATTACHMENT_OPTIMAL. */
static void drawHost(const Options* o, Scene* s, const float* viewProjection) {
    VkRenderingAttachmentInfo colour, depth;
    VkRenderingInfo rendering;
    VkViewport viewport;
    VkRect2D scissor;
    VkDeviceSize offset = 0;
    Draw draw;
    const float light = o->black ? 0.0f : 1.0f;
    const int stencil = o->depthFormat == VK_FORMAT_D24_UNORM_S8_UINT ||
                        o->depthFormat == VK_FORMAT_D32_SFLOAT_S8_UINT;

    barrier(s->cmd, s->colour.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
            VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    barrier(s->cmd, s->depth.image,
            VK_IMAGE_ASPECT_DEPTH_BIT | (stencil ? VK_IMAGE_ASPECT_STENCIL_BIT : 0),
            VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    memset(&colour, 0, sizeof colour);
    colour.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
    colour.imageView = s->colour.view;
    colour.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colour.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colour.clearValue.color.float32[0] = 0.35f * light; /* the host's sky */
    colour.clearValue.color.float32[1] = 0.45f * light;
    colour.clearValue.color.float32[2] = 0.6f * light;
    colour.clearValue.color.float32[3] = 1.0f;
    depth = colour;
    depth.imageView = s->depth.view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    depth.clearValue.depthStencil.depth = 1.0f;
    depth.clearValue.depthStencil.stencil = 0;
    memset(&rendering, 0, sizeof rendering);
    rendering.sType = VK_STRUCTURE_TYPE_RENDERING_INFO;
    rendering.renderArea.extent.width = o->width;
    rendering.renderArea.extent.height = o->height;
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &colour;
    rendering.pDepthAttachment = &depth;
    if (stencil) rendering.pStencilAttachment = &depth;
    vkCmdBeginRendering(s->cmd, &rendering);
    /* A viewport of positive height: the projection's y is flipped instead (clipYDown). */
    viewport.x = 0.0f;
    viewport.y = 0.0f;
    viewport.width = (float)o->width;
    viewport.height = (float)o->height;
    viewport.minDepth = 0.0f;
    viewport.maxDepth = 1.0f;
    scissor.offset.x = scissor.offset.y = 0;
    scissor.extent.width = o->width;
    scissor.extent.height = o->height;
    vkCmdSetViewport(s->cmd, 0, 1, &viewport);
    vkCmdSetScissor(s->cmd, 0, 1, &scissor);
    vkCmdBindPipeline(s->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, s->pipeline);
    memcpy(draw.viewProjection, viewProjection, sizeof draw.viewProjection);

    draw.colour[0] = 0.45f * light; /* the floor: warm grey */
    draw.colour[1] = 0.42f * light;
    draw.colour[2] = 0.38f * light;
    draw.colour[3] = 1.0f;
    vkCmdPushConstants(s->cmd, s->layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                       0, sizeof draw, &draw);
    vkCmdBindVertexBuffers(s->cmd, 0, 1, &s->floorPositions.buffer, &offset);
    vkCmdBindVertexBuffers(s->cmd, 1, 1, &s->floorNormals.buffer, &offset);
    vkCmdDraw(s->cmd, 6, 1, 0, 0);

    draw.colour[0] = 0.85f * light; /* the character: pale blue */
    draw.colour[1] = 0.9f * light;
    draw.colour[2] = 1.0f * light;
    vkCmdPushConstants(s->cmd, s->layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                       0, sizeof draw, &draw);
    vkCmdBindVertexBuffers(s->cmd, 0, 1, &s->positions.buffer, &offset);
    vkCmdBindVertexBuffers(s->cmd, 1, 1, &s->normals.buffer, &offset);
    vkCmdBindIndexBuffer(s->cmd, s->indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(s->cmd, s->indexCount, 1, 0, 0, 0);
    vkCmdEndRendering(s->cmd);
}

static void copyColour(const Options* o, Scene* s, const Buffer* to) {
    VkBufferImageCopy region;
    memset(&region, 0, sizeof region);
    region.imageSubresource.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
    region.imageSubresource.layerCount = 1;
    region.imageExtent.width = o->width;
    region.imageExtent.height = o->height;
    region.imageExtent.depth = 1;
    vkCmdCopyImageToBuffer(s->cmd, s->colour.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           to->buffer, 1, &region);
}

/* One frame: the host's drawing, motionfx's effects over it, submitted and waited for. */
static int runFrame(const Host* host, const Options* o, Scene* s, long frame) {
    const double time = (double)frame / (double)s->info.framesPerSecond;
    const int save = frame == o->save;
    VkCommandBufferBeginInfo begin;
    VkSubmitInfo submit;
    MfxFrameDesc desc;
    MfxResult result;
    float viewProjection[16];
    int c;

    if (mfxGetCharacterMesh(s->effects, time, (float*)s->positions.mapped,
                            (float*)s->normals.mapped, NULL) != MFX_SUCCESS)
        return 0;
    memset(&desc, 0, sizeof desc);
    desc.structVersion = MFX_FRAME_DESC_VERSION;
    desc.time = time;
    desc.width = o->width;
    desc.height = o->height;
    /* The scene's own camera, as the host's: its y flipped for a viewport of positive height. */
    if (mfxGetSceneCamera(s->effects, (float)o->width / (float)o->height, &desc.camera) !=
        MFX_SUCCESS)
        return 0;
    for (c = 0; c < 4; ++c)
        desc.camera.projection[c * 4 + 1] = -desc.camera.projection[c * 4 + 1];
    desc.camera.clipYDown = 1;
    multiply(desc.camera.projection, desc.camera.view, viewProjection);

    memset(&begin, 0, sizeof begin);
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    if (vkBeginCommandBuffer(s->cmd, &begin) != VK_SUCCESS) return 0;
    if (s->pipeline != VK_NULL_HANDLE) drawHost(o, s, viewProjection);
    desc.commandBuffer = s->cmd;
    desc.colour.image = s->colour.image;
    desc.colour.format = COLOUR_FORMAT;
    desc.colour.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    desc.colour.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    if (save) { /* the host's own picture, before motionfx draws into it */
        barrier(s->cmd, s->colour.image, VK_IMAGE_ASPECT_COLOR_BIT,
                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        copyColour(o, s, &s->readbackUnder);
        desc.colour.layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    }
    desc.depth.image = s->depth.image;
    desc.depth.format = o->depthFormat;
    desc.depth.layout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    desc.depth.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
    if (o->hostAnimation) { /* the host's own animation system would fill these */
        if (mfxGetCharacterNodeMatrices(s->effects, time, s->nodeMatrices) != MFX_SUCCESS) {
            vkEndCommandBuffer(s->cmd);
            return 0;
        }
        desc.nodeMatrices = s->nodeMatrices;
        desc.nodeMatrixCount = s->nodeCount;
    }
    result = mfxRecordFrame(s->effects, &desc);
    if (result != MFX_SUCCESS) {
        vkEndCommandBuffer(s->cmd);
        return 0;
    }
    if (save) copyColour(o, s, &s->readback);
    if (vkEndCommandBuffer(s->cmd) != VK_SUCCESS) return 0;
    memset(&submit, 0, sizeof submit);
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &s->cmd;
    if (vkQueueSubmit(host->queue, 1, &submit, s->fence) != VK_SUCCESS ||
        vkWaitForFences(host->device, 1, &s->fence, VK_TRUE, UINT64_MAX) != VK_SUCCESS ||
        vkResetFences(host->device, 1, &s->fence) != VK_SUCCESS) {
        fprintf(stderr, "motionfx_host: the frame's submission failed\n");
        return 0;
    }
    if (save) {
        char path[4096];
        snprintf(path, sizeof path, "%s/under_%04ld.ppm", o->out, frame);
        if (!writePpm(path, (const unsigned char*)s->readbackUnder.mapped, o->width, o->height))
            return 0;
        snprintf(path, sizeof path, "%s/frame_%04ld.ppm", o->out, frame);
        if (!writePpm(path, (const unsigned char*)s->readback.mapped, o->width, o->height))
            return 0;
        printf("wrote %s\n", path);
    }
    return 1;
}

int main(int argc, char** argv) {
    Host host;
    Options options;
    MfxRuntimeDesc desc;
    MfxRuntime runtime = NULL;
    uint32_t version, e;
    int status = 0;

    if (!parseOptions(argc, argv, &options)) return 2;
    if (!makeHost(&host, options.validate)) {
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
    printf("motionfx %u.%u.%u runtime on %s\n", version / 10000, version / 100 % 100, version % 100,
           mfxRuntimeDeviceName(runtime));

    if (options.sceneFile != NULL) {
        Scene scene;
        long frames, f;
        memset(&scene, 0, sizeof scene);
        if (!makeScene(&host, runtime, &options, &scene)) {
            status = 1;
        } else {
            printf("%s: %u effects, %u smoke grids, %u frames at %g fps\n", options.sceneFile,
                   scene.info.effectCount, scene.info.smokeGrids, scene.info.frameCount,
                   (double)scene.info.framesPerSecond);
            for (e = 0; e < scene.info.effectCount; ++e)
                printf("  %s\n", mfxEffectName(scene.effects, e));
            frames = options.frames >= 0 ? options.frames : (long)scene.info.frameCount;
            for (f = 0; f < frames && status == 0; ++f)
                if (!runFrame(&host, &options, &scene, f)) status = 1;
            if (status == 0 && frames > 0)
                printf("drew %ld frames of %ux%u with the effects\n", frames, options.width,
                       options.height);
        }
        destroyScene(&host, &scene);
    }

    mfxDestroyRuntime(runtime);
    destroyHost(&host);
    if (options.validate) {
        printf("validation: %u messages\n", host.validationMessages);
        if (host.validationMessages > 0 && status == 0) status = 3;
    }
    return status;
}
