// OpenEXR output for HDR flipbook sheets (`motionfx bake --hdr`): a single-part scanline file,
// uncompressed, with half-float R, G, B and A channels (linear, premultiplied), as the OpenEXR
// file layout specifies it ("OpenEXR File Layout", openexr.com): the magic number and version,
// the header's attributes (channels, compression, dataWindow, displayWindow, lineOrder,
// pixelAspectRatio, screenWindowCenter, screenWindowWidth), the offset table of the scanlines,
// and each scanline as its y, its byte count and its channels' values one channel after another
// in the header's (alphabetical) order.
#pragma once

#include "core/result.h"

#include <cstdint>
#include <span>
#include <string>

namespace mfx::render {

// Writes RGBA floats (top row first, 4 a pixel) as half-float channels; non-finite values are
// written as 0 and values beyond half's range as its largest.
Status writeExr(const std::string& path, uint32_t width, uint32_t height,
                std::span<const float> rgba);

} // namespace mfx::render
