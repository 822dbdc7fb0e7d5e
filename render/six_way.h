// Six-way lighting maps for baked smoke (`motionfx bake --six-way`, docs/flipbook.md): the smoke
// drawn six times, each lit by one white light from one of the six directions of the bake camera's
// frame (right, top, back and left, bottom, front: back is the far side of the smoke, front the
// camera's), kept as one light value a pixel (its luminance, Rec. 709 weights), and packed as
// Unity's six-way smoke takes them: sheet A = (right, top, back, opacity), sheet B = (left,
// bottom, front, emission). An engine lights a pixel from a light whose direction toward the light
// is l in that frame by the blend
//     light = sum over the six axes a of w_a m_a,   w_a = max(0, l . a)^2,
// the squared cosines, which sum to 1 for a unit l: a light along an axis gives that axis's map
// alone, and the light every direction shares (the march's ambient share) passes through
// unchanged. Maps are stored straight (not premultiplied by the opacity) and divided by a scale
// (the largest value, in the metadata), linear 8-bit: value = stored / 255 * scale.
#pragma once

#include "render/flipbook.h"
#include "render/scene_camera.h"

#include <array>
#include <glm/glm.hpp>

namespace mfx::render {

// The six directions toward the light, in world space, in sheet order: right, top, back, left,
// bottom, front of `camera`'s frame.
std::array<glm::vec3, 6> sixWayDirections(const SceneCamera& camera);
// The blend's weights for a light whose direction toward the light is `towardLight` (world
// space, any length), in sheet order.
std::array<float, 6> sixWayWeights(const SceneCamera& camera, glm::vec3 towardLight);

// Luminance (Rec. 709) of a premultiplied linear colour.
float luminance(const float* rgb);

// One frame's maps, premultiplied by opacity: a = (right, top, back, opacity), b = (left, bottom,
// front, emission).
struct SixWayCell {
    CellImage a, b;
};
// The largest straight value among the six light maps (channels 0-2 of a and b) and of the
// emission (b's alpha) over `cells`, each at least a small floor.
struct SixWayScales {
    float light = 1.0f, emission = 1.0f;
};
SixWayScales sixWayScales(std::span<const SixWayCell> cells);
// The cell's two sheets' pixels (RGBA8 each; straight maps over their scales, opacity linear).
std::array<std::vector<uint8_t>, 2> encodeSixWay(const SixWayCell& cell,
                                                 const SixWayScales& scales);
// The blend above on stored cells (RGBA8 each): premultiplied light (the opacity times the blend
// of the maps, in all three colour channels) and the opacity, emission left out.
CellImage relightSixWay(std::span<const uint8_t> a, std::span<const uint8_t> b, uint32_t width,
                        uint32_t height, const SixWayScales& scales,
                        const std::array<float, 6>& weights);

} // namespace mfx::render
