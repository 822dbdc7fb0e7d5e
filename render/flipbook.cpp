#include "render/flipbook.h"

#include "render/render_target.h"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace mfx::render {

namespace {

// "AxB" as two numbers, or "A" alone when `single` (both then A); false when it is neither.
bool parsePair(const std::string& text, bool single, uint32_t& a, uint32_t& b) {
    auto number = [](std::string_view part, uint32_t& out) {
        if (part.empty() || part.size() > 9) return false;
        auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), out);
        return error == std::errc() && end == part.data() + part.size();
    };
    const size_t x = text.find('x');
    if (x == std::string::npos) {
        if (!single || !number(text, a)) return false;
        b = a;
        return true;
    }
    return number(std::string_view(text).substr(0, x), a) &&
           number(std::string_view(text).substr(x + 1), b);
}

} // namespace

Status parseFlipbookGrid(const std::string& text, FlipbookLayout& layout) {
    uint32_t columns = 0, rows = 0;
    if (!parsePair(text, false, columns, rows))
        return Error{"--grid '" + text + "' is not COLUMNSxROWS, e.g. 8x8"};
    if (columns == 0 || rows == 0 || columns > kMaxFlipbookColumns || rows > kMaxFlipbookColumns)
        return Error{"--grid '" + text + "': columns and rows must be 1 to " +
                     std::to_string(kMaxFlipbookColumns)};
    layout.columns = columns;
    layout.rows = rows;
    return Ok{};
}

Status parseFlipbookCell(const std::string& text, uint32_t maxSide, FlipbookLayout& layout) {
    uint32_t width = 0, height = 0;
    if (!parsePair(text, true, width, height))
        return Error{"--cell '" + text + "' is not N or WIDTHxHEIGHT pixels, e.g. 256 or 256x128"};
    const uint32_t widest = maxSide / layout.columns, tallest = maxSide / layout.rows;
    if (width < kMinCellSide || height < kMinCellSide || width > widest || height > tallest)
        return Error{"--cell '" + text + "': with a " + std::to_string(layout.columns) + "x" +
                     std::to_string(layout.rows) + " grid a cell must be " +
                     std::to_string(kMinCellSide) + " to " + std::to_string(widest) +
                     " pixels wide and " + std::to_string(kMinCellSide) + " to " +
                     std::to_string(tallest) + " high (the sheet at most " +
                     std::to_string(maxSide) + " pixels a side)"};
    const uint64_t pixels = uint64_t(width) * layout.columns * height * layout.rows;
    if (pixels > kMaxSheetPixels)
        return Error{"--cell '" + text + "': with a " + std::to_string(layout.columns) + "x" +
                     std::to_string(layout.rows) + " grid the sheet would be " +
                     std::to_string(width * layout.columns) + "x" +
                     std::to_string(height * layout.rows) + " pixels; at most " +
                     std::to_string(kMaxSheetPixels) + " pixels (8192x8192) are baked at once"};
    layout.cellWidth = width;
    layout.cellHeight = height;
    return Ok{};
}

Result<std::vector<uint32_t>> sampleFrames(uint32_t first, uint32_t last, uint32_t count) {
    if (last < first || count == 0) return Error{"no frames to bake"};
    const uint32_t available = last - first + 1;
    if (count > available)
        return Error{"frames " + std::to_string(first) + " to " + std::to_string(last) + " are " +
                     std::to_string(available) + " frames, fewer than the " +
                     std::to_string(count) +
                     " pictures the sheet needs: give a smaller --grid, a longer --frames range "
                     "or a shorter --loop"};
    std::vector<uint32_t> frames(count, first);
    for (uint32_t k = 1; k < count; ++k)
        frames[k] = first + uint32_t(std::lround(double(k) * (available - 1) / (count - 1)));
    return frames;
}

namespace {

// crossFadeLoop over pictures or fields: `values` picks the numbers of one.
template <class Picture, class Values>
std::vector<Picture> crossFade(std::vector<Picture> frames, uint32_t overlap, Values values) {
    if (overlap == 0) return frames;
    const size_t cells = frames.size() - overlap;
    std::vector<Picture> out;
    out.reserve(cells);
    for (size_t i = 0; i < cells; ++i)
        out.push_back(std::move(frames[overlap + i]));
    for (uint32_t j = 0; j < overlap; ++j) {
        std::vector<float>& cell = values(out[cells - overlap + j]);
        const std::vector<float>& start = values(frames[j]);
        const float w = float(j + 1) / float(overlap + 1);
        for (size_t k = 0; k < cell.size(); ++k)
            cell[k] = (1.0f - w) * cell[k] + w * start[k];
    }
    return out;
}

} // namespace

std::vector<CellImage> crossFadeLoop(std::vector<CellImage> frames, uint32_t overlap) {
    return crossFade(
        std::move(frames), overlap, [](auto& p) -> auto& { return p.rgba; });
}

std::vector<MotionField> crossFadeLoop(std::vector<MotionField> fields, uint32_t overlap) {
    return crossFade(
        std::move(fields), overlap, [](auto& f) -> auto& { return f.xy; });
}

void sampleCell(const CellImage& image, float x, float y, float out[4]) {
    const float fx = x - 0.5f, fy = y - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float ax = fx - x0f, ay = fy - y0f;
    for (int c = 0; c < 4; ++c)
        out[c] = 0.0f;
    // Outside the picture by more than a pixel (or not a number): nothing to blend.
    if (!(x0f >= -2.0f && x0f <= float(image.width) + 1.0f && y0f >= -2.0f &&
          y0f <= float(image.height) + 1.0f))
        return;
    const long x0 = long(x0f), y0 = long(y0f);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const long px = x0 + i, py = y0 + j;
            if (px < 0 || py < 0 || px >= long(image.width) || py >= long(image.height)) continue;
            const float w = (i ? ax : 1.0f - ax) * (j ? ay : 1.0f - ay);
            const float* texel = image.at(uint32_t(px), uint32_t(py));
            for (int c = 0; c < 4; ++c)
                out[c] += w * texel[c];
        }
}

CellImage blendCells(const CellImage& a, const CellImage& b, const MotionField* motion, float t) {
    CellImage out(a.width, a.height);
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x) {
            float mx = 0.0f, my = 0.0f;
            if (motion) {
                const float* m = &motion->xy[(size_t(y) * a.width + x) * 2];
                mx = m[0];
                my = m[1];
            }
            const float px = float(x) + 0.5f, py = float(y) + 0.5f;
            float from[4], to[4];
            sampleCell(a, px - t * mx, py - t * my, from);
            sampleCell(b, px + (1.0f - t) * mx, py + (1.0f - t) * my, to);
            float* o = out.at(x, y);
            for (int c = 0; c < 4; ++c)
                o[c] = (1.0f - t) * from[c] + t * to[c];
        }
    return out;
}

double coveredMeanError(const CellImage& x, const CellImage& y,
                        std::span<const CellImage* const> cover) {
    double sum = 0.0;
    size_t covered = 0;
    const size_t pixels = size_t(x.width) * x.height;
    for (size_t p = 0; p < pixels; ++p) {
        bool any = false;
        for (const CellImage* image : cover)
            for (int c = 0; c < 4 && !any; ++c)
                any = image->rgba[p * 4 + c] > 0.0f;
        if (!any) continue;
        ++covered;
        for (int c = 0; c < 4; ++c)
            sum += std::abs(double(x.rgba[p * 4 + c]) - double(y.rgba[p * 4 + c]));
    }
    return covered ? sum / double(covered * 4) : 0.0;
}

float motionScale(std::span<const MotionField> fields) {
    float largest = 0.0f;
    for (const MotionField& field : fields)
        for (size_t k = 0; k < field.xy.size(); ++k) {
            const float side = float(k % 2 ? field.height : field.width);
            if (std::isfinite(field.xy[k]))
                largest = std::max(largest, std::abs(field.xy[k]) / side);
        }
    return std::max(largest, 1e-4f);
}

std::vector<uint8_t> encodeMotion(const MotionField& field, float scale) {
    const size_t pixels = size_t(field.width) * field.height;
    std::vector<uint8_t> rgba(pixels * 4);
    const float side[2] = {float(field.width), float(field.height)};
    for (size_t p = 0; p < pixels; ++p) {
        for (int c = 0; c < 2; ++c) {
            float m = field.xy[p * 2 + c] / side[c] / scale;
            if (!std::isfinite(m)) m = 0.0f;
            const float encoded = std::clamp(0.5f + 0.5f * m, 0.0f, 1.0f);
            rgba[p * 4 + c] = uint8_t(std::lround(encoded * 255.0f));
        }
        rgba[p * 4 + 2] = 0;
        rgba[p * 4 + 3] = 255;
    }
    return rgba;
}

MotionField decodeMotion(std::span<const uint8_t> rgba, uint32_t width, uint32_t height,
                         float scale) {
    MotionField field(width, height);
    const float side[2] = {float(width), float(height)};
    for (size_t p = 0; p < size_t(width) * height; ++p)
        for (int c = 0; c < 2; ++c)
            field.xy[p * 2 + c] = (float(rgba[p * 4 + c]) / 255.0f * 2.0f - 1.0f) * scale * side[c];
    return field;
}

void toneMapCell(CellImage& cell, float exposureStops, bool aces) {
    const float scale = std::exp2(exposureStops);
    for (size_t k = 0; k < cell.rgba.size(); ++k) {
        if (k % 4 == 3) continue;
        float x = cell.rgba[k];
        x = std::isfinite(x) ? std::clamp(x, 0.0f, 65504.0f) * scale : 0.0f;
        if (aces) x = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
        cell.rgba[k] = std::clamp(x, 0.0f, 1.0f);
    }
}

std::vector<uint8_t> encodeColour8(const CellImage& linear) {
    std::vector<uint8_t> rgba(linear.rgba.size());
    for (size_t k = 0; k < rgba.size(); ++k) {
        float v = linear.rgba[k];
        if (!std::isfinite(v)) v = 0.0f;
        v = std::clamp(v, 0.0f, 1.0f);
        rgba[k] = k % 4 == 3 ? uint8_t(std::lround(v * 255.0f)) : encodeSrgb8(v);
    }
    return rgba;
}

std::vector<uint8_t> previewOver(std::span<const uint8_t> colour, const float background[3]) {
    auto decode = [](uint8_t v) {
        const float c = float(v) / 255.0f;
        return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    };
    std::vector<uint8_t> out(colour.size());
    for (size_t p = 0; p + 3 < colour.size(); p += 4) {
        const float a = float(colour[p + 3]) / 255.0f;
        for (int c = 0; c < 3; ++c)
            out[p + c] = encodeSrgb8(
                std::clamp(decode(colour[p + c]) + (1.0f - a) * background[c], 0.0f, 1.0f));
        out[p + 3] = 255;
    }
    return out;
}

CellImage cellFromRgba8(std::span<const uint8_t> rgba, uint32_t width, uint32_t height) {
    CellImage cell(width, height);
    for (size_t k = 0; k < cell.rgba.size(); ++k)
        cell.rgba[k] = float(rgba[k]) / 255.0f;
    return cell;
}

void placeCell(std::vector<uint8_t>& sheet, const FlipbookLayout& layout, uint32_t index,
               std::span<const uint8_t> cell) {
    const size_t x0 = size_t(index % layout.columns) * layout.cellWidth;
    const size_t y0 = size_t(index / layout.columns) * layout.cellHeight;
    const size_t row = size_t(layout.cellWidth) * 4;
    for (uint32_t y = 0; y < layout.cellHeight; ++y)
        std::copy_n(cell.data() + y * row, row,
                    sheet.data() + ((y0 + y) * layout.sheetWidth() + x0) * 4);
}

std::vector<uint8_t> cellOfSheet(std::span<const uint8_t> sheet, const FlipbookLayout& layout,
                                 uint32_t index) {
    const size_t x0 = size_t(index % layout.columns) * layout.cellWidth;
    const size_t y0 = size_t(index / layout.columns) * layout.cellHeight;
    const size_t row = size_t(layout.cellWidth) * 4;
    std::vector<uint8_t> cell(row * layout.cellHeight);
    for (uint32_t y = 0; y < layout.cellHeight; ++y)
        std::copy_n(sheet.data() + ((y0 + y) * layout.sheetWidth() + x0) * 4, row,
                    cell.data() + y * row);
    return cell;
}

} // namespace mfx::render
