// The flipbook player on the GPU (shaders/render/flipbook_player.*, docs/flipbook.md): a baked
// sheet and its motion vectors played on a quad, blended between cells as render/flipbook.h's
// blendCells does on the CPU. What a game's material does, here to check that the sheets play
// as measured.
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "render/render_target.h"
#include "shaders/shared/flipbook.h"

namespace mfx::render {

class FlipbookPlayer {
public:
    // Draws into targets of kSceneColorFormat, single-sampled.
    explicit FlipbookPlayer(const gpu::Context& ctx);

    // Records one picture of the sheets (each a sampled image in SHADER_READ_ONLY_OPTIMAL, read
    // as stored: UNORM) into `target`, cleared to transparent black first, at `play`.
    void record(VkCommandBuffer cmd, RenderTarget& target, gpu::Image& colour, gpu::Image& motion,
                const shared::FlipbookPlay& play);

private:
    gpu::Program program_;
    gpu::UniqueSampler sampler_;
};

} // namespace mfx::render
