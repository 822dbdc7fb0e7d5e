// The effects drawn into a host application's frame (the runtime library, runtime/runtime.cpp):
// the host gives its colour and depth images, in layouts it names, and a camera; motionfx draws
// the effects (EffectsRenderer, the same passes as its own frames) into a layer of its own whose
// depth is a copy of the host's, then lays the layer over the host's colour and leaves both images
// in the layouts the host asked for.
//
//   1. hostDepth (shaders/render/host_depth.frag): the host's depth, of any of the formats below,
//      copied into the layer's 32-bit depth, every sample of a pixel alike;
//   2. the effects and the smoke (EffectsRenderer) over that depth into the layer's colour,
//      cleared to transparent black: premultiplied colour and coverage, multisampled and resolved;
//   3. layerComposite (shaders/render/layer_composite.frag): the layer over the host's colour,
//      out = layer.rgb + (1 - layer.a) host, by the blend stage in the host format's own space.
//
// A premultiplied "over" is associative, so drawing the effects into a transparent layer and
// laying it over the picture gives what drawing them onto the picture gives (FrameRenderer), up to
// the rounding of the layer's fp16 and, at the host's silhouettes, the one depth per pixel the
// host's single-sampled depth has.
#pragma once

#include "core/result.h"
#include "render/effects_renderer.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mfx::render {

// One of the host's images: 2D, one mip level and array layer, single-sampled.
struct HostImage {
    VkImage image = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;      // when motionfx's commands begin
    VkImageLayout finalLayout = VK_IMAGE_LAYOUT_UNDEFINED; // when they end
};

struct HostTargets {
    uint32_t width = 0, height = 0;
    HostImage colour; // made with COLOR_ATTACHMENT usage, a format the device blends into
    HostImage depth;  // made with SAMPLED usage, one of kHostDepthFormats
};

// The depth formats a host may give, as their names.
inline constexpr VkFormat kHostDepthFormats[] = {VK_FORMAT_D16_UNORM, VK_FORMAT_X8_D24_UNORM_PACK32,
                                                 VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D32_SFLOAT,
                                                 VK_FORMAT_D32_SFLOAT_S8_UINT};

// "VK_FORMAT_R8G8B8A8_SRGB" for the formats a host is likely to give, else "VkFormat <number>".
std::string formatName(VkFormat format);

class HostFrame {
public:
    // The effects of `simulation`'s scene, drawn with `samples` samples a pixel (fewer where the
    // device has fewer).
    HostFrame(const gpu::Context& ctx, const sim::SceneSimulation& simulation,
              VkSampleCountFlagBits samples);

    // Whether motionfx can draw into `targets`: one line naming the first thing that is wrong
    // (a size, a null image, a format the device cannot blend into or sample, a layout).
    Status check(const HostTargets& targets) const;

    // Records, into the host's command buffer: with `frame`, the simulation's frame `frame` and
    // the effect passes' advance; then the effects at scene time `time` from `camera`, laid over
    // the host's colour. `targets` must pass check(). The previous recording must have finished
    // executing (the layer and the views made for the host's images are reused or freed here).
    // With `frame` and `pose`, the simulation's frame has the character in that pose (the host's
    // animation; SceneSimulation::recordFrame).
    void record(VkCommandBuffer cmd, sim::SceneSimulation& simulation, const uint32_t* frame,
                float time, const SceneCamera& camera, const HostTargets& targets,
                const anim::Pose* pose = nullptr);

private:
    gpu::Program& compositeFor(VkFormat format);
    VkImageView viewOf(const HostImage& image, VkImageAspectFlags aspect);

    const gpu::Context& ctx_;
    VkSampleCountFlagBits samples_;
    EffectsRenderer effects_;
    std::optional<RenderTarget> layer_;
    gpu::Program depthCopy_;
    std::map<VkFormat, gpu::Program> composites_; // by the host colour's format
    gpu::UniqueSampler sampler_;
    // Views of the host's images made for the last recording, freed by the next one (the host's
    // images may change from frame to frame: a resized swapchain).
    std::vector<gpu::UniqueImageView> views_;
};

} // namespace mfx::render
