#include "render/six_way.h"

#include <algorithm>
#include <cmath>

namespace mfx::render {

std::array<glm::vec3, 6> sixWayDirections(const SceneCamera& camera) {
    // The view matrix's rows are the camera's axes in world space: x right, y up, z toward the
    // viewer; the far side of the smoke (back) is -z.
    const glm::mat4& v = camera.view;
    const glm::vec3 right = glm::normalize(glm::vec3(v[0][0], v[1][0], v[2][0]));
    const glm::vec3 up = glm::normalize(glm::vec3(v[0][1], v[1][1], v[2][1]));
    const glm::vec3 towardViewer = glm::normalize(glm::vec3(v[0][2], v[1][2], v[2][2]));
    return {right, up, -towardViewer, -right, -up, towardViewer};
}

std::array<float, 6> sixWayWeights(const SceneCamera& camera, glm::vec3 towardLight) {
    const float length = glm::length(towardLight);
    const glm::vec3 l = length > 0.0f ? towardLight / length : glm::vec3(0.0f);
    const std::array<glm::vec3, 6> axes = sixWayDirections(camera);
    std::array<float, 6> w{};
    for (size_t i = 0; i < 6; ++i) {
        const float c = std::max(glm::dot(l, axes[i]), 0.0f);
        w[i] = c * c;
    }
    return w;
}

float luminance(const float* rgb) {
    return 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2];
}

SixWayScales sixWayScales(std::span<const SixWayCell> cells) {
    SixWayScales scales{1e-4f, 1e-4f};
    for (const SixWayCell& cell : cells)
        for (size_t p = 0; p < size_t(cell.a.width) * cell.a.height; ++p) {
            const float alpha = cell.a.rgba[p * 4 + 3];
            if (!(alpha > 1.0f / 255.0f)) continue;
            for (int c = 0; c < 3; ++c)
                scales.light = std::max(
                    {scales.light, cell.a.rgba[p * 4 + c] / alpha, cell.b.rgba[p * 4 + c] / alpha});
            scales.emission = std::max(scales.emission, cell.b.rgba[p * 4 + 3] / alpha);
        }
    return scales;
}

std::array<std::vector<uint8_t>, 2> encodeSixWay(const SixWayCell& cell,
                                                 const SixWayScales& scales) {
    const size_t pixels = size_t(cell.a.width) * cell.a.height;
    std::array<std::vector<uint8_t>, 2> out{std::vector<uint8_t>(pixels * 4),
                                            std::vector<uint8_t>(pixels * 4)};
    auto byte = [](float v) {
        return uint8_t(std::lround(std::clamp(std::isfinite(v) ? v : 0.0f, 0.0f, 1.0f) * 255.0f));
    };
    for (size_t p = 0; p < pixels; ++p) {
        const float alpha = cell.a.rgba[p * 4 + 3];
        const float straight = alpha > 1.0f / 255.0f ? 1.0f / alpha : 0.0f;
        for (int c = 0; c < 3; ++c) {
            out[0][p * 4 + c] = byte(cell.a.rgba[p * 4 + c] * straight / scales.light);
            out[1][p * 4 + c] = byte(cell.b.rgba[p * 4 + c] * straight / scales.light);
        }
        out[0][p * 4 + 3] = byte(alpha);
        out[1][p * 4 + 3] = byte(cell.b.rgba[p * 4 + 3] * straight / scales.emission);
    }
    return out;
}

CellImage relightSixWay(std::span<const uint8_t> a, std::span<const uint8_t> b, uint32_t width,
                        uint32_t height, const SixWayScales& scales,
                        const std::array<float, 6>& weights) {
    CellImage out(width, height);
    for (size_t p = 0; p < size_t(width) * height; ++p) {
        const float alpha = float(a[p * 4 + 3]) / 255.0f;
        float light = 0.0f;
        for (int c = 0; c < 3; ++c)
            light += weights[size_t(c)] * float(a[p * 4 + c]) +
                     weights[size_t(c) + 3] * float(b[p * 4 + c]);
        light *= scales.light / 255.0f * alpha;
        for (int c = 0; c < 3; ++c)
            out.rgba[p * 4 + c] = light;
        out.rgba[p * 4 + 3] = alpha;
    }
    return out;
}

} // namespace mfx::render
