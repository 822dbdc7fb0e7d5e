#include "render/host_frame.h"

#include "core/gpu/check.h"
#include "core/gpu/context.h"
#include "shaders/embedded.h"
#include "sim/scene_simulation.h"

#include <algorithm>
#include <iterator>

namespace mfx::render {

std::string formatName(VkFormat format) {
    switch (format) {
#define MFX_FORMAT(name)                                                                           \
    case VK_FORMAT_##name:                                                                         \
        return "VK_FORMAT_" #name;
        MFX_FORMAT(UNDEFINED)
        MFX_FORMAT(R8G8B8A8_UNORM)
        MFX_FORMAT(R8G8B8A8_SRGB)
        MFX_FORMAT(B8G8R8A8_UNORM)
        MFX_FORMAT(B8G8R8A8_SRGB)
        MFX_FORMAT(A2B10G10R10_UNORM_PACK32)
        MFX_FORMAT(A2R10G10B10_UNORM_PACK32)
        MFX_FORMAT(B10G11R11_UFLOAT_PACK32)
        MFX_FORMAT(R16G16B16A16_SFLOAT)
        MFX_FORMAT(R16G16B16A16_UNORM)
        MFX_FORMAT(R32G32B32A32_SFLOAT)
        MFX_FORMAT(R8_UNORM)
        MFX_FORMAT(R32_SFLOAT)
        MFX_FORMAT(R32_UINT)
        MFX_FORMAT(D16_UNORM)
        MFX_FORMAT(D16_UNORM_S8_UINT)
        MFX_FORMAT(X8_D24_UNORM_PACK32)
        MFX_FORMAT(D24_UNORM_S8_UINT)
        MFX_FORMAT(D32_SFLOAT)
        MFX_FORMAT(D32_SFLOAT_S8_UINT)
        MFX_FORMAT(S8_UINT)
#undef MFX_FORMAT
    default:
        return "VkFormat " + std::to_string(int(format));
    }
}

namespace {

std::string layoutName(VkImageLayout layout) {
    switch (layout) {
#define MFX_LAYOUT(name)                                                                           \
    case VK_IMAGE_LAYOUT_##name:                                                                   \
        return "VK_IMAGE_LAYOUT_" #name;
        MFX_LAYOUT(UNDEFINED)
        MFX_LAYOUT(GENERAL)
        MFX_LAYOUT(COLOR_ATTACHMENT_OPTIMAL)
        MFX_LAYOUT(DEPTH_STENCIL_ATTACHMENT_OPTIMAL)
        MFX_LAYOUT(DEPTH_STENCIL_READ_ONLY_OPTIMAL)
        MFX_LAYOUT(SHADER_READ_ONLY_OPTIMAL)
        MFX_LAYOUT(TRANSFER_SRC_OPTIMAL)
        MFX_LAYOUT(TRANSFER_DST_OPTIMAL)
        MFX_LAYOUT(PREINITIALIZED)
        MFX_LAYOUT(DEPTH_ATTACHMENT_OPTIMAL)
        MFX_LAYOUT(DEPTH_READ_ONLY_OPTIMAL)
        MFX_LAYOUT(PRESENT_SRC_KHR)
        MFX_LAYOUT(ATTACHMENT_OPTIMAL)
        MFX_LAYOUT(READ_ONLY_OPTIMAL)
#undef MFX_LAYOUT
    default:
        return "VkImageLayout " + std::to_string(int(layout));
    }
}

bool hasStencil(VkFormat format) {
    return format == VK_FORMAT_D24_UNORM_S8_UINT || format == VK_FORMAT_D32_SFLOAT_S8_UINT ||
           format == VK_FORMAT_D16_UNORM_S8_UINT || format == VK_FORMAT_S8_UINT;
}

bool isDepthOrStencil(VkFormat format) {
    return hasStencil(format) || format == VK_FORMAT_D16_UNORM ||
           format == VK_FORMAT_X8_D24_UNORM_PACK32 || format == VK_FORMAT_D32_SFLOAT;
}

// Layouts only a depth or stencil image can be in.
bool isDepthLayout(VkImageLayout layout) {
    switch (layout) {
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_STENCIL_ATTACHMENT_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_STENCIL_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_STENCIL_ATTACHMENT_OPTIMAL:
    case VK_IMAGE_LAYOUT_STENCIL_READ_ONLY_OPTIMAL:
        return true;
    default:
        return false;
    }
}

// Layouts only a colour image can be in.
bool isColourLayout(VkImageLayout layout) {
    return layout == VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL ||
           layout == VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
}

// The first thing wrong with the layouts of `image` ("colour" or "depth"), or empty.
std::string layoutProblem(const char* which, const HostImage& image, bool depth) {
    const std::string name = which;
    if (image.layout == VK_IMAGE_LAYOUT_UNDEFINED || image.layout == VK_IMAGE_LAYOUT_PREINITIALIZED)
        return name + ".layout is " + layoutName(image.layout) +
               ": give the layout the image is in when the frame's commands reach motionfx's "
               "(its contents would be lost)";
    if (image.finalLayout == VK_IMAGE_LAYOUT_UNDEFINED ||
        image.finalLayout == VK_IMAGE_LAYOUT_PREINITIALIZED)
        return name + ".finalLayout is " + layoutName(image.finalLayout) +
               ": give the layout to leave the image in";
    for (VkImageLayout layout : {image.layout, image.finalLayout})
        if (depth ? isColourLayout(layout) : isDepthLayout(layout))
            return name + (layout == image.layout ? ".layout " : ".finalLayout ") +
                   layoutName(layout) + " is a layout for " +
                   (depth ? "colour images, not depth ones" : "depth images, not colour ones");
    return {};
}

gpu::DescriptorWrite bindView(uint32_t binding, VkImageView view, VkImageLayout layout,
                              VkSampler sampler) {
    gpu::DescriptorWrite write;
    write.binding = binding;
    write.image = {sampler, view, layout};
    write.isImage = true;
    return write;
}

} // namespace

HostFrame::HostFrame(const gpu::Context& ctx, const sim::SceneSimulation& simulation,
                     VkSampleCountFlagBits samples)
    : ctx_(ctx), samples_(supportedSamples(ctx, samples)), effects_(ctx, simulation, samples_),
      sampler_(gpu::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE)) {
    gpu::GraphicsProgramDesc desc;
    desc.name = "host_depth";
    desc.vertex = shaders::fullscreen_vert;
    desc.fragment = shaders::host_depth_frag;
    desc.depthFormat = kDepthFormat;
    desc.depthTest = true;
    desc.depthWrite = true;
    desc.depthCompare = VK_COMPARE_OP_ALWAYS;
    desc.samples = samples_;
    depthCopy_ = gpu::createGraphicsProgram(ctx, desc);
}

Status HostFrame::check(const HostTargets& targets) const {
    const uint32_t largest = ctx_.limits().maxImageDimension2D;
    if (targets.width == 0 || targets.height == 0 || targets.width > largest ||
        targets.height > largest)
        return Error{"width and height must be 1 to " + std::to_string(largest) +
                     " on this device; got " + std::to_string(targets.width) + "x" +
                     std::to_string(targets.height)};
    if (targets.colour.image == VK_NULL_HANDLE) return Error{"colour.image is null"};
    if (targets.depth.image == VK_NULL_HANDLE) return Error{"depth.image is null"};

    VkFormatProperties colour{}, depth{};
    vkGetPhysicalDeviceFormatProperties(ctx_.physicalDevice(), targets.colour.format, &colour);
    vkGetPhysicalDeviceFormatProperties(ctx_.physicalDevice(), targets.depth.format, &depth);
    if (isDepthOrStencil(targets.colour.format) ||
        !(colour.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT))
        return Error{"colour.format " + formatName(targets.colour.format) +
                     " is not a colour format this device can blend into (the effects are laid "
                     "over the host's colour by blending)"};
    const bool known = std::find(std::begin(kHostDepthFormats), std::end(kHostDepthFormats),
                                 targets.depth.format) != std::end(kHostDepthFormats);
    if (!known) {
        std::string list;
        for (VkFormat f : kHostDepthFormats)
            list += (list.empty() ? "" : ", ") + formatName(f);
        return Error{"depth.format " + formatName(targets.depth.format) +
                     " is not a depth format motionfx reads; give one of " + list};
    }
    if (!(depth.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT))
        return Error{"depth.format " + formatName(targets.depth.format) +
                     " cannot be sampled on this device (motionfx reads the host's depth in a "
                     "shader); give another of its depth formats"};
    std::string problem = layoutProblem("colour", targets.colour, false);
    if (problem.empty()) problem = layoutProblem("depth", targets.depth, true);
    if (!problem.empty()) return Error{problem};
    return Ok{};
}

gpu::Program& HostFrame::compositeFor(VkFormat format) {
    auto found = composites_.find(format);
    if (found != composites_.end()) return found->second;
    gpu::GraphicsProgramDesc desc;
    desc.name = "layer_composite";
    desc.vertex = shaders::fullscreen_vert;
    desc.fragment = shaders::layer_composite_frag;
    desc.colorFormats = {format};
    desc.blend = gpu::BlendMode::PremultipliedAlpha;
    return composites_.emplace(format, gpu::createGraphicsProgram(ctx_, desc)).first->second;
}

VkImageView HostFrame::viewOf(const HostImage& image, VkImageAspectFlags aspect) {
    VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    info.image = image.image;
    info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    info.format = image.format;
    info.subresourceRange = {aspect, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateImageView(ctx_.device(), &info, nullptr, &view));
    views_.emplace_back(ctx_.device(), view);
    return view;
}

void HostFrame::record(VkCommandBuffer cmd, sim::SceneSimulation& simulation, const uint32_t* frame,
                       float time, const SceneCamera& camera, const HostTargets& targets,
                       const anim::Pose* pose) {
    views_.clear(); // the previous recording has finished executing
    if (!layer_ || layer_->width != targets.width || layer_->height != targets.height)
        layer_ = createRenderTarget(ctx_, targets.width, targets.height, samples_);
    RenderTarget& layer = *layer_;

    effects_.setCamera(camera);
    if (frame) {
        simulation.recordFrame(cmd, *frame, pose);
        effects_.advance(cmd, simulation, *frame);
    }

    // 1. The host's depth into the layer's, every sample alike.
    const HostImage& hostDepth = targets.depth;
    const VkImageAspectFlags depthAspects =
        VK_IMAGE_ASPECT_DEPTH_BIT |
        (hasStencil(hostDepth.format) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
    const VkImageView depthView = viewOf(hostDepth, VK_IMAGE_ASPECT_DEPTH_BIT);
    gpu::imageBarrier(cmd, hostDepth.image, depthAspects, hostDepth.layout,
                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    gpu::Image& depth = samples_ != VK_SAMPLE_COUNT_1_BIT ? layer.msaaDepth : layer.depth;
    gpu::imageBarrier(
        cmd, depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
        VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
            VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
    VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depthAttachment.imageView = depth.view.get();
    depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE; // every sample is written
    depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {targets.width, targets.height}};
    rendering.layerCount = 1;
    rendering.pDepthAttachment = &depthAttachment;
    vkCmdBeginRendering(cmd, &rendering);
    setWholeViewport(cmd, layer);
    depthCopy_.bind(
        cmd, {bindView(0, depthView, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler_.get())});
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
    gpu::imageBarrier(cmd, hostDepth.image, depthAspects, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      hostDepth.finalLayout, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                      VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);

    // 2. The effects and the smoke into the layer, cleared to transparent black.
    beginRenderingOverDepth(cmd, layer, glm::vec4(0.0f), effects_.fadesAgainstDepth());
    effects_.drawEffects(cmd, layer, simulation, time);
    effects_.drawSmoke(cmd, layer, simulation);

    // 3. The layer over the host's colour.
    gpu::imageBarrier(cmd, layer.color, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    const HostImage& hostColour = targets.colour;
    const VkImageView colourView = viewOf(hostColour, VK_IMAGE_ASPECT_COLOR_BIT);
    gpu::imageBarrier(
        cmd, hostColour.image, hostColour.layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
        VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
        VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    VkRenderingAttachmentInfo colourAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    colourAttachment.imageView = colourView;
    colourAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colourAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    colourAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    rendering.pDepthAttachment = nullptr;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &colourAttachment;
    vkCmdBeginRendering(cmd, &rendering);
    setWholeViewport(cmd, layer);
    compositeFor(hostColour.format)
        .bind(cmd, {gpu::bindImage(0, layer.color, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                   sampler_.get())});
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
    gpu::imageBarrier(cmd, hostColour.image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                      hostColour.finalLayout, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                      VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

} // namespace mfx::render
