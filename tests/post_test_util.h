// What the bloom and tone-map tests share: a scene target filled with given linear colours.
#pragma once

#include "core/gpu/resources.h"
#include "render/render_target.h"

#include <glm/gtc/packing.hpp>
#include <vector>

namespace mfx::test {

// Fills `target`'s colour with `rgba` (linear, 4 floats a pixel, top row first) as half floats,
// left as if the scene had just been drawn into it.
inline void fillSceneColour(const gpu::Context& ctx, render::RenderTarget& target,
                            const std::vector<float>& rgba) {
    std::vector<uint16_t> halves(rgba.size());
    for (size_t i = 0; i < rgba.size(); ++i)
        halves[i] = glm::packHalf1x16(rgba[i]);
    gpu::uploadImage(ctx, target.color, std::as_bytes(std::span<const uint16_t>(halves)),
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
}

} // namespace mfx::test
