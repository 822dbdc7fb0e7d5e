// The effects as a layer of their own, for compositing (`motionfx render --layers`): from the
// full frame F and the same frame drawn without its effects C (the character and the stage), an
// RGBA image L with premultiplied colour such that laying it over C,
//     out = L.rgb + (1 - L.a) C,
// on the 8-bit values as stored (what a compositor does with the PNGs), gives F again. Per pixel
// L.a is the least alpha that keeps the colour a valid premultiplied one, 0 <= L.rgb <= L.a:
// where an effect darkens a channel (F < C) it must cover C by at least 1 - F / C, where it
// brightens it (F > C) by at least (F - C) / (1 - C). Where the effects change nothing L is
// transparent black. Both bloom and tone map are in F and C alike.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace mfx::render {

// The layer (RGBA8, premultiplied) from `full` and `under` (RGBA8 each, same size).
std::vector<uint8_t> effectsLayer(std::span<const uint8_t> full, std::span<const uint8_t> under);

// `layer` (premultiplied RGBA8) laid over `under` (RGBA8): the composite, alpha 255.
std::vector<uint8_t> compositeOver(std::span<const uint8_t> layer, std::span<const uint8_t> under);

} // namespace mfx::render
