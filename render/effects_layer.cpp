#include "render/effects_layer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mfx::render {

std::vector<uint8_t> effectsLayer(std::span<const uint8_t> full, std::span<const uint8_t> under) {
    if (full.size() != under.size() || full.size() % 4 != 0)
        throw std::invalid_argument("effectsLayer: the two frames differ in size");
    std::vector<uint8_t> layer(full.size(), 0);
    for (size_t p = 0; p < full.size(); p += 4) {
        float alpha = 0.0f;
        for (int c = 0; c < 3; ++c) {
            const float f = float(full[p + c]) / 255.0f, u = float(under[p + c]) / 255.0f;
            if (f < u) alpha = std::max(alpha, 1.0f - f / u);
            if (f > u) alpha = std::max(alpha, (f - u) / (1.0f - u));
        }
        // Stored as 8 bits: rounded up, so the bounds still hold.
        const uint8_t a = uint8_t(std::min(255.0f, std::ceil(alpha * 255.0f - 1e-3f)));
        const float stored = float(a) / 255.0f;
        for (int c = 0; c < 3; ++c) {
            const float colour = float(full[p + c]) - (1.0f - stored) * float(under[p + c]);
            layer[p + c] = uint8_t(std::lround(std::clamp(colour, 0.0f, float(a))));
        }
        layer[p + 3] = a;
    }
    return layer;
}

std::vector<uint8_t> compositeOver(std::span<const uint8_t> layer, std::span<const uint8_t> under) {
    if (layer.size() != under.size() || layer.size() % 4 != 0)
        throw std::invalid_argument("compositeOver: the layer and the picture differ in size");
    std::vector<uint8_t> out(layer.size(), 255);
    for (size_t p = 0; p < layer.size(); p += 4) {
        const float cover = 1.0f - float(layer[p + 3]) / 255.0f;
        for (int c = 0; c < 3; ++c)
            out[p + c] = uint8_t(
                std::lround(std::min(255.0f, float(layer[p + c]) + cover * float(under[p + c]))));
    }
    return out;
}

} // namespace mfx::render
