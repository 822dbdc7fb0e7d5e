// On-screen text without a font file or a shader: a 5x7 pixel capital-letter font whose lit
// pixels are cleared as small rectangles into the colour attachment of the current rendering
// (vkCmdClearAttachments). Enough for a viewer's status line: frame time, frame number, state.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string_view>
#include <vulkan/vulkan.h>

namespace mfx::render {

// Width and height in pixels of `text` drawn at `scale` (one font pixel = scale x scale).
glm::uvec2 textSize(std::string_view text, uint32_t scale);

// Records `text` (letters are drawn as capitals; characters without a glyph as blanks) with its
// top-left corner at `origin` pixels, over a `background` box with one font pixel of margin, into
// colour attachment 0 of the rendering in progress. `limit` is the attachment's size: pixels
// outside it are not drawn.
void drawText(VkCommandBuffer cmd, std::string_view text, glm::ivec2 origin, uint32_t scale,
              const glm::vec4& colour, const glm::vec4& background, VkExtent2D limit);

} // namespace mfx::render
