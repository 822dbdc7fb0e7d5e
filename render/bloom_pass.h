// The bloom: bright parts of the picture spread light around them, as a camera lens does. The
// picture (linear HDR colour) is down-sampled level by level to a pyramid of half, quarter, ...
// size, the levels are summed back up from the coarsest, and the picture is replaced in place by
// mix(picture, sum / levels, strength). Both filters keep the mean (shaders/render/
// bloom_common.glsl), so the bloom keeps the picture's total light, and a point's glow reaches
// further the brighter it is. Follows J. Jimenez, "Next Generation Post Processing in Call of
// Duty: Advanced Warfare" (SIGGRAPH 2014), without the threshold: nothing is cut off.
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"

#include <vector>

namespace mfx::render {

class BloomPass {
public:
    explicit BloomPass(const gpu::Context& ctx);

    // Records the bloom of `picture` (a kSceneColorFormat image with storage and sampled usage,
    // after its last write as a colour attachment) with `strength` in (0, 1]; leaves it in the
    // GENERAL layout, its writes visible to fragment shaders.
    void record(VkCommandBuffer cmd, gpu::Image& picture, float strength);

    // Levels of the pyramid for a picture of `width` x `height`: one more half-size level while
    // the smaller side of the last is at least 8 texels, at least 1 and at most kMaxLevels.
    static uint32_t levelCount(uint32_t width, uint32_t height);
    static constexpr uint32_t kMaxLevels = 7;

private:
    void prepare(uint32_t width, uint32_t height);

    const gpu::Context& ctx_;
    gpu::Program downsample_, upsample_, composite_;
    gpu::UniqueSampler sampler_;
    std::vector<gpu::Image> down_; // down_[0]: half the picture's size
    std::vector<gpu::Image> up_;   // up_[i]: down_[i] plus every coarser level, tent-filtered
    uint32_t width_ = 0, height_ = 0;
};

} // namespace mfx::render
