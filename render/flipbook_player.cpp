#include "render/flipbook_player.h"

#include "shaders/embedded.h"

namespace mfx::render {

FlipbookPlayer::FlipbookPlayer(const gpu::Context& ctx)
    : sampler_(gpu::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE)) {
    gpu::GraphicsProgramDesc desc;
    desc.name = "flipbook_player";
    desc.vertex = shaders::flipbook_player_vert;
    desc.fragment = shaders::flipbook_player_frag;
    desc.pushConstantSize = sizeof(shared::FlipbookPlay);
    desc.colorFormats = {kSceneColorFormat};
    desc.depthFormat = kDepthFormat;
    program_ = gpu::createGraphicsProgram(ctx, desc);
}

void FlipbookPlayer::record(VkCommandBuffer cmd, RenderTarget& target, gpu::Image& colour,
                            gpu::Image& motion, const shared::FlipbookPlay& play) {
    beginRendering(cmd, target, glm::vec4(0.0f));
    program_.bind(
        cmd, {gpu::bindImage(0, colour, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler_.get()),
              gpu::bindImage(1, motion, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, sampler_.get())});
    program_.push(cmd, play);
    vkCmdDraw(cmd, 6, 1, 0, 0);
    endRendering(cmd);
}

} // namespace mfx::render
