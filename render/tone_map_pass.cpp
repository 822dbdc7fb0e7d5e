#include "render/tone_map_pass.h"

#include "shaders/embedded.h"
#include "shaders/shared/post.h"

#include <cmath>

namespace mfx::render {

ToneMapPass::ToneMapPass(const gpu::Context& ctx)
    : sampler_(gpu::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE)) {
    gpu::GraphicsProgramDesc desc;
    desc.name = "tone_map";
    desc.vertex = shaders::fullscreen_vert;
    desc.fragment = shaders::tone_map_frag;
    desc.pushConstantSize = sizeof(shared::ToneMapDraw);
    desc.colorFormats = {kOutputColorFormat};
    program_ = gpu::createGraphicsProgram(ctx, desc);
}

void ToneMapPass::record(VkCommandBuffer cmd, gpu::Image& picture, RenderTarget& output,
                         const scene::PostSpec& post) {
    // The picture's last writes: its rendering (colour attachment) or the bloom (compute).
    const VkImageLayout read = picture.layout == VK_IMAGE_LAYOUT_GENERAL
                                   ? VK_IMAGE_LAYOUT_GENERAL
                                   : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    gpu::imageBarrier(cmd, picture, read,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT |
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    gpu::imageBarrier(cmd, output.color, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT,
                      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                      VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    beginColourRendering(cmd, output, VK_ATTACHMENT_LOAD_OP_DONT_CARE); // every pixel is written
    program_.bind(cmd, {gpu::bindImage(0, picture, read, sampler_.get())});
    shared::ToneMapDraw d{};
    d.exposureScale = std::exp2(post.exposure);
    d.toneMap = post.toneMap == scene::ToneMap::Aces ? MFX_TONE_MAP_ACES : MFX_TONE_MAP_NONE;
    program_.push(cmd, d);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
}

} // namespace mfx::render
