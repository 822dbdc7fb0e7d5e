#include "render/optical_flow.h"

#include <algorithm>
#include <cmath>

namespace mfx::render {

namespace {

// Half the size (rounded up), each pixel the mean of the (up to) four it covers.
CellImage halve(const CellImage& image) {
    CellImage out((image.width + 1) / 2, (image.height + 1) / 2);
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            float* o = out.at(x, y);
            float n = 0.0f;
            for (uint32_t j = 0; j < 2; ++j)
                for (uint32_t i = 0; i < 2; ++i) {
                    const uint32_t sx = 2 * x + i, sy = 2 * y + j;
                    if (sx >= image.width || sy >= image.height) continue;
                    const float* s = image.at(sx, sy);
                    for (int c = 0; c < 4; ++c)
                        o[c] += s[c];
                    n += 1.0f;
                }
            for (int c = 0; c < 4; ++c)
                o[c] /= n;
        }
    return out;
}

// The coarser level's flow on the finer level's pixels: interpolated, scaled by the size ratio.
MotionField upsample(const MotionField& coarse, uint32_t width, uint32_t height) {
    MotionField out(width, height);
    const float sx = float(width) / float(coarse.width), sy = float(height) / float(coarse.height);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const float cx =
                std::clamp((float(x) + 0.5f) / sx - 0.5f, 0.0f, float(coarse.width - 1));
            const float cy =
                std::clamp((float(y) + 0.5f) / sy - 0.5f, 0.0f, float(coarse.height - 1));
            const uint32_t x0 = uint32_t(cx), y0 = uint32_t(cy);
            const uint32_t x1 = std::min(x0 + 1, coarse.width - 1);
            const uint32_t y1 = std::min(y0 + 1, coarse.height - 1);
            const float ax = cx - float(x0), ay = cy - float(y0);
            for (int c = 0; c < 2; ++c) {
                auto at = [&](uint32_t px, uint32_t py) {
                    return coarse.xy[(size_t(py) * coarse.width + px) * 2 + c];
                };
                const float v = (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x1, y0)) +
                                ay * ((1 - ax) * at(x0, y1) + ax * at(x1, y1));
                out.xy[(size_t(y) * width + x) * 2 + c] = v * (c == 0 ? sx : sy);
            }
        }
    return out;
}

// Central difference of channel c along x (axis 0) or y (axis 1), one-sided at the edges.
float derivative(const CellImage& image, uint32_t x, uint32_t y, int c, int axis) {
    const uint32_t size = axis == 0 ? image.width : image.height;
    const uint32_t at = axis == 0 ? x : y;
    const uint32_t lo = at > 0 ? at - 1 : at, hi = at + 1 < size ? at + 1 : at;
    if (lo == hi) return 0.0f;
    const float a = axis == 0 ? image.at(lo, y)[c] : image.at(x, lo)[c];
    const float b = axis == 0 ? image.at(hi, y)[c] : image.at(x, hi)[c];
    return (b - a) / float(hi - lo);
}

// One pyramid level: `flow` refined in place (warps x iterations).
void refine(const CellImage& from, const CellImage& to, MotionField& flow,
            const FlowOptions& options) {
    const uint32_t w = from.width, h = from.height;
    const size_t pixels = size_t(w) * h;
    const float alpha2 = options.smoothness * options.smoothness;
    std::vector<float> m(pixels * 3), b(pixels * 2), start(pixels * 2);
    CellImage warped(w, h);
    for (uint32_t warp = 0; warp < options.warps; ++warp) {
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                const float* f = &flow.xy[(size_t(y) * w + x) * 2];
                sampleCell(to, float(x) + 0.5f + f[0], float(y) + 0.5f + f[1], warped.at(x, y));
            }
        start = flow.xy;
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                const size_t p = size_t(y) * w + x;
                float mxx = 0, mxy = 0, myy = 0, bx = 0, by = 0;
                for (int c = 0; c < 4; ++c) {
                    const float ix =
                        0.5f * (derivative(from, x, y, c, 0) + derivative(warped, x, y, c, 0));
                    const float iy =
                        0.5f * (derivative(from, x, y, c, 1) + derivative(warped, x, y, c, 1));
                    const float it = warped.at(x, y)[c] - from.at(x, y)[c];
                    mxx += ix * ix;
                    mxy += ix * iy;
                    myy += iy * iy;
                    bx += ix * it;
                    by += iy * it;
                }
                m[p * 3] = mxx;
                m[p * 3 + 1] = mxy;
                m[p * 3 + 2] = myy;
                // The right-hand side's constant part: M f - b.
                b[p * 2] = mxx * start[p * 2] + mxy * start[p * 2 + 1] - bx;
                b[p * 2 + 1] = mxy * start[p * 2] + myy * start[p * 2 + 1] - by;
            }
        // Gauss-Seidel sweeps of (M + alpha^2) u = alpha^2 mean(neighbours) + M f - b.
        for (uint32_t it = 0; it < options.iterations; ++it)
            for (uint32_t y = 0; y < h; ++y)
                for (uint32_t x = 0; x < w; ++x) {
                    const size_t p = size_t(y) * w + x;
                    float mean[2] = {0.0f, 0.0f};
                    float n = 0.0f;
                    auto add = [&](size_t q) {
                        mean[0] += flow.xy[q * 2];
                        mean[1] += flow.xy[q * 2 + 1];
                        n += 1.0f;
                    };
                    if (x > 0) add(p - 1);
                    if (x + 1 < w) add(p + 1);
                    if (y > 0) add(p - w);
                    if (y + 1 < h) add(p + w);
                    if (n > 0.0f) {
                        mean[0] /= n;
                        mean[1] /= n;
                    }
                    const float a = m[p * 3] + alpha2, c = m[p * 3 + 1], d = m[p * 3 + 2] + alpha2;
                    const float rx = alpha2 * mean[0] + b[p * 2];
                    const float ry = alpha2 * mean[1] + b[p * 2 + 1];
                    const float det = a * d - c * c; // > 0: M is positive semi-definite
                    flow.xy[p * 2] = (d * rx - c * ry) / det;
                    flow.xy[p * 2 + 1] = (a * ry - c * rx) / det;
                }
    }
}

} // namespace

MotionField opticalFlow(const CellImage& from, const CellImage& to, const FlowOptions& options) {
    std::vector<CellImage> fromLevels{from}, toLevels{to};
    const uint32_t coarsest = std::max(options.coarsest, 2u);
    while (std::min(fromLevels.back().width, fromLevels.back().height) / 2 >= coarsest) {
        fromLevels.push_back(halve(fromLevels.back()));
        toLevels.push_back(halve(toLevels.back()));
    }
    MotionField flow(fromLevels.back().width, fromLevels.back().height);
    for (size_t level = fromLevels.size(); level-- > 0;) {
        const CellImage& f = fromLevels[level];
        if (flow.width != f.width || flow.height != f.height)
            flow = upsample(flow, f.width, f.height);
        refine(f, toLevels[level], flow, options);
    }
    return flow;
}

} // namespace mfx::render
