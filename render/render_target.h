// An offscreen render target: a colour image and a depth image of one size, rendered to with
// dynamic rendering and read back for PNG output and tests; and the 8-bit output image a frame's
// tone map writes.
#pragma once

#include "core/gpu/resources.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace mfx::render {

// The scene is drawn in linear HDR colour (values above 1 are kept for the bloom and the tone
// map); the output is sRGB, encoded by the target on write.
inline constexpr VkFormat kSceneColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kOutputColorFormat = VK_FORMAT_R8G8B8A8_SRGB;
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

struct RenderTarget {
    gpu::Image color; // single-sampled: what is read back (the resolve target with MSAA)
    gpu::Image depth; // single-sampled: sample 0 of each pixel with MSAA
    gpu::Image msaaColor, msaaDepth; // what is drawn into when samples > 1
    // A copy of `depth` after the opaque scene, sampled by the effects that fade in front of it
    // (copyFadeDepth).
    gpu::Image fadeDepth;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    uint32_t width = 0;
    uint32_t height = 0;
};

// Colour of kSceneColorFormat (attachment, transfer source and destination, sampled, storage) and
// depth (attachment, transfer source, sampled), and with `samples` > 1 multisampled colour and
// depth drawn into and resolved at the end of rendering (colour averaged, depth from sample 0).
// Pipelines drawing into it need the same sample count.
RenderTarget createRenderTarget(const gpu::Context& ctx, uint32_t width, uint32_t height,
                                VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);
// Colour alone, single-sampled, of kOutputColorFormat (attachment, transfer source): the picture
// as written to files and windows.
RenderTarget createOutputTarget(const gpu::Context& ctx, uint32_t width, uint32_t height);

// The largest sample count up to `wanted` that the device supports for both colour and depth.
VkSampleCountFlagBits supportedSamples(const gpu::Context& ctx, VkSampleCountFlagBits wanted);

// Transitions the images to attachment layouts and begins rendering, clearing colour to
// `clearColor` (linear) and depth to 1; sets viewport and scissor to the whole target. With MSAA
// the multisampled images are resolved into `color` and `depth` when rendering ends, and kept
// when `resumable` (for resumeRendering).
void beginRendering(VkCommandBuffer cmd, RenderTarget& target, const glm::vec4& clearColor,
                    bool resumable = false);
// The same with the depth the target holds kept (loaded, not cleared): a layer drawn over a depth
// put there before (HostFrame).
void beginRenderingOverDepth(VkCommandBuffer cmd, RenderTarget& target, const glm::vec4& clearColor,
                             bool resumable = false);
void endRendering(VkCommandBuffer cmd);
// After a resumable rendering has ended: copies the (resolved) depth into `fadeDepth`, left
// shader-read-only for the passes that sample it.
void copyFadeDepth(VkCommandBuffer cmd, RenderTarget& target);
// Begins rendering again over what a resumable rendering left (colour and depth loaded), resolved
// again at its end.
void resumeRendering(VkCommandBuffer cmd, RenderTarget& target);

// Begins rendering into the single-sampled colour alone (no depth), in the attachment layout
// already, with `load` (LOAD keeps what it holds, DONT_CARE for a pass that writes every pixel);
// same viewport.
void beginColourRendering(VkCommandBuffer cmd, RenderTarget& target, VkAttachmentLoadOp load);

// Begins rendering over what the single-sampled colour already holds (loaded, no depth), for
// composite passes after beginRendering/endRendering; same viewport.
void beginCompositing(VkCommandBuffer cmd, RenderTarget& target);

// The whole target as viewport (flipped: +y up in clip space) and scissor.
void setWholeViewport(VkCommandBuffer cmd, const RenderTarget& target);

// RGBA8 rows, top row first (sRGB-encoded values, as a PNG stores them). A scene target's linear
// colour is clamped to [0, 1] and encoded as the output target would encode it.
std::vector<uint8_t> readColor(const gpu::Context& ctx, RenderTarget& target);
// Linear RGBA as floats, top row first, of a scene target (kSceneColorFormat).
std::vector<float> readLinearColor(const gpu::Context& ctx, RenderTarget& target);
// The sRGB encoding of a linear value in [0, 1], rounded to 8 bits.
uint8_t encodeSrgb8(float linear);
// Depth in [0, 1] per pixel, top row first; 1 where nothing was drawn.
std::vector<float> readDepth(const gpu::Context& ctx, RenderTarget& target);

} // namespace mfx::render
