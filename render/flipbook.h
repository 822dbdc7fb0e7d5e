// Flipbooks: an effect's frames baked into one sheet of cells (`motionfx bake`), the form game
// engines play smoke and trails in when they cannot simulate them. This file is the part that needs
// no GPU: the sheet's layout, which frames become cells, the loop's cross-fade, the 8-bit encoding
// of the colour and motion-vector sheets, and the player's blend on the CPU (the twin of
// shaders/render/flipbook_player.frag), with which the bake measures how well its sheets play.
//
// Cells run left to right, then top to bottom: cell i is in column i % columns, row i / columns,
// row 0 at the top of the sheet (the PNG's first row). Within a cell, uv runs from its top-left
// corner (0, 0) to its bottom-right one (1, 1), as the image's rows do.
//
// Motion vectors (docs/flipbook.md): cell i's motion is the displacement, in its own uv units,
// that takes each of its pixels to where that content is in cell i + 1 (for the last cell of a
// loop, cell 0). The player blends cells a and b = a + 1 at a fraction t in [0, 1] by
//     out(uv) = (1 - t) a(uv - t m(uv)) + t b(uv + (1 - t) m(uv)),   m = a's motion,
// so content moves along its motion instead of fading out in one place and in at another (a plain
// cross-fade is m = 0). The sheet stores m per channel as
//     rg = 0.5 + 0.5 m / scale   (8 bits; scale in the metadata: the largest |m| component),
// b = 0 and a = 1.
#pragma once

#include "core/result.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace mfx::render {

// The largest sheet side the bake writes (and most engines import), and the most pixels a sheet
// may have (8192 x 8192, or 16384 x 4096: the bake holds a few float copies of every cell).
inline constexpr uint32_t kMaxSheetSide = 16384;
inline constexpr uint64_t kMaxSheetPixels = uint64_t(8192) * 8192;
inline constexpr uint32_t kMaxFlipbookColumns = 64;
inline constexpr uint32_t kMinCellSide = 8;

struct FlipbookLayout {
    uint32_t columns = 8, rows = 8;
    uint32_t cellWidth = 256, cellHeight = 256;

    uint32_t cells() const { return columns * rows; }
    uint32_t sheetWidth() const { return columns * cellWidth; }
    uint32_t sheetHeight() const { return rows * cellHeight; }
};

// "--grid COLUMNSxROWS", each 1 to kMaxFlipbookColumns: the error is one line naming the option.
Status parseFlipbookGrid(const std::string& text, FlipbookLayout& layout);
// "--cell N" (square) or "WxH" pixels, each at least kMinCellSide, with the sheet (the grid's
// columns and rows of cells, parsed first) at most `maxSide` a side and kMaxSheetPixels in all.
Status parseFlipbookCell(const std::string& text, uint32_t maxSide, FlipbookLayout& layout);

// The `count` scene frames sampled evenly from first..last (inclusive, both ends taken when
// count > 1, rounded to the nearest frame); an error when the range has fewer than `count` frames
// (a flipbook never repeats a frame).
Result<std::vector<uint32_t>> sampleFrames(uint32_t first, uint32_t last, uint32_t count);

// A cell's picture: RGBA floats, premultiplied, top row first.
struct CellImage {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;

    CellImage() = default;
    CellImage(uint32_t w, uint32_t h) : width(w), height(h), rgba(size_t(w) * h * 4, 0.0f) {}
    float* at(uint32_t x, uint32_t y) { return &rgba[(size_t(y) * width + x) * 4]; }
    const float* at(uint32_t x, uint32_t y) const { return &rgba[(size_t(y) * width + x) * 4]; }
};

// The seamless loop: `frames` holds cells + overlap pictures in time order; the result's cell i is
// frame overlap + i, and the last `overlap` cells are cross-faded toward the first frames: cell
// cells - overlap + j (j < overlap) is (1 - w) frame(cells + j) + w frame(j), w = (j + 1) /
// (overlap + 1). Its last cell then leads into frame overlap - 1 (mostly), which leads into cell 0.
std::vector<CellImage> crossFadeLoop(std::vector<CellImage> frames, uint32_t overlap);

// Per-pixel motion of a cell, in pixels (x right, y down), toward the next cell.
struct MotionField {
    uint32_t width = 0, height = 0;
    std::vector<float> xy; // 2 per pixel, top row first

    MotionField() = default;
    MotionField(uint32_t w, uint32_t h) : width(w), height(h), xy(size_t(w) * h * 2, 0.0f) {}
};
// The same cross-fade for the cells' motion fields.
std::vector<MotionField> crossFadeLoop(std::vector<MotionField> fields, uint32_t overlap);

// Bilinear sample of `image` at pixel coordinates (x, y) (pixel centres at +0.5), transparent
// black outside the picture.
void sampleCell(const CellImage& image, float x, float y, float out[4]);

// The player's blend (above) of `a` toward `b` at `t`, with a's motion in pixels (null: a
// cross-fade).
CellImage blendCells(const CellImage& a, const CellImage& b, const MotionField* motion, float t);

// The mean absolute difference of two pictures' channels over the pixels where any of `cover`
// (pictures of the same size) is not transparent black; 0 where none is.
double coveredMeanError(const CellImage& x, const CellImage& y,
                        std::span<const CellImage* const> cover);

// The motion sheet's scale: the largest |component| of the fields' motion in uv units, or a small
// floor where nothing moves.
float motionScale(std::span<const MotionField> fields);
// A field's 8-bit encoding (above), RGBA rows, and back (in pixels of a cell of its size).
std::vector<uint8_t> encodeMotion(const MotionField& field, float scale);
MotionField decodeMotion(std::span<const uint8_t> rgba, uint32_t width, uint32_t height,
                         float scale);

// The scene's exposure (stops) and tone curve (ACES when `aces`, else a clamp; the tone map pass's,
// shaders/render/tone_map.frag) applied to a layer's premultiplied linear colour, alpha kept.
void toneMapCell(CellImage& cell, float exposureStops, bool aces);

// A cell as the colour sheet stores it (RGBA8: colour sRGB-encoded, alpha linear, premultiplied
// in linear light) and back (floats of the encoded values over 255; no decode: what a blend in the
// texture's own values does).
std::vector<uint8_t> encodeColour8(const CellImage& linear);
CellImage cellFromRgba8(std::span<const uint8_t> rgba, uint32_t width, uint32_t height);

// The colour sheet (as stored) laid over an opaque background of linear colour `background`:
// what it looks like blended as documented, for a preview picture (RGBA8, alpha 255).
std::vector<uint8_t> previewOver(std::span<const uint8_t> colour, const float background[3]);

// Copies `cell` (RGBA8, the layout's cell size) into cell `index` of `sheet` (RGBA8, the layout's
// sheet size), and the reverse.
void placeCell(std::vector<uint8_t>& sheet, const FlipbookLayout& layout, uint32_t index,
               std::span<const uint8_t> cell);
std::vector<uint8_t> cellOfSheet(std::span<const uint8_t> sheet, const FlipbookLayout& layout,
                                 uint32_t index);

} // namespace mfx::render
