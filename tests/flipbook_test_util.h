// Pictures with known motion for the flipbook tests (test_flipbook.cpp, test_flipbook_player.cpp).
#pragma once

#include "render/flipbook.h"

#include <algorithm>
#include <cmath>

namespace mfx::test {

// A soft disc of radius r at (cx, cy) on a size x size picture, premultiplied orange with some
// texture inside (so the flow has gradients there too), on transparent black.
inline render::CellImage disc(uint32_t size, float cx, float cy, float r) {
    render::CellImage image(size, size);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const float d = std::hypot(float(x) + 0.5f - cx, float(y) + 0.5f - cy);
            const float a = std::clamp((r - d) / 4.0f + 0.5f, 0.0f, 1.0f);
            const float shade =
                0.75f + 0.25f * std::sin(0.4f * (float(x) - cx)) * std::cos(0.3f * (float(y) - cy));
            float* p = image.at(x, y);
            p[0] = a * shade;
            p[1] = a * 0.5f * shade;
            p[2] = a * 0.1f;
            p[3] = a;
        }
    return image;
}

} // namespace mfx::test
