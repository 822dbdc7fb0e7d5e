// The tone map: the scene target's linear HDR colour, scaled by the exposure, through the scene's
// tone curve into the 8-bit sRGB output (shaders/render/tone_map.frag). One full-screen triangle.
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/scene/scene.h"
#include "render/render_target.h"

namespace mfx::render {

class ToneMapPass {
public:
    explicit ToneMapPass(const gpu::Context& ctx);

    // Records the mapping of `picture`'s colour (written before as a colour attachment or, after a
    // bloom, in GENERAL) into `output` (createOutputTarget, same size).
    void record(VkCommandBuffer cmd, gpu::Image& picture, RenderTarget& output,
                const scene::PostSpec& post);

private:
    gpu::Program program_;
    gpu::UniqueSampler sampler_;
};

} // namespace mfx::render
