// Image output: output directories and PNG files, with errors a user can act on.
#pragma once

#include "core/result.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace mfx::render {

// Creates `directory` (and its parents) if needed; fails when it cannot be created or is not a
// writable directory.
Status ensureOutputDirectory(const std::string& directory);

// Writes RGBA8 rows (top row first) as a PNG.
Status writePng(const std::string& path, uint32_t width, uint32_t height,
                std::span<const uint8_t> rgba);

struct RgbaImage {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba; // top row first
};
// Reads a PNG (any channel count) as RGBA8; fails with the file name and the decoder's reason.
Result<RgbaImage> readPng(const std::string& path);

} // namespace mfx::render
