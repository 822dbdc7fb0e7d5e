#include "render/image_output.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stb_image.h>
#include <stb_image_write.h>
#include <unistd.h>

namespace mfx::render {

Status ensureOutputDirectory(const std::string& directory) {
    namespace fs = std::filesystem;
    if (directory.empty()) return Error{"the output directory name is empty"};
    std::error_code error;
    if (fs::exists(directory, error) && !fs::is_directory(directory, error))
        return Error{"output directory " + directory + " exists and is not a directory"};
    fs::create_directories(directory, error);
    if (error) return Error{"cannot create output directory " + directory + ": " + error.message()};
    if (::access(directory.c_str(), W_OK | X_OK) != 0)
        return Error{"output directory " + directory + " is not writable: " + std::strerror(errno)};
    return Ok{};
}

Status writePng(const std::string& path, uint32_t width, uint32_t height,
                std::span<const uint8_t> rgba) {
    if (width == 0 || height == 0 || rgba.size() != size_t(width) * height * 4)
        return Error{"cannot write " + path + ": image data does not match " +
                     std::to_string(width) + "x" + std::to_string(height) + " RGBA"};
    // Probe with an ordinary open first: stb reports failure without a reason.
    {
        std::ofstream probe(path, std::ios::binary | std::ios::trunc);
        if (!probe) return Error{"cannot write " + path + ": " + std::strerror(errno)};
    }
    const int ok =
        stbi_write_png(path.c_str(), int(width), int(height), 4, rgba.data(), int(width * 4));
    if (ok == 0) return Error{"cannot write " + path + ": PNG encoding or writing failed"};
    return Ok{};
}

Result<RgbaImage> readPng(const std::string& path) {
    int w = 0, h = 0, channels = 0;
    stbi_uc* pixels = stbi_load(path.c_str(), &w, &h, &channels, 4);
    if (!pixels) {
        const char* reason = stbi_failure_reason();
        return Error{"cannot read " + path + ": " + (reason ? reason : "unknown reason")};
    }
    RgbaImage image{uint32_t(w), uint32_t(h), {}};
    image.rgba.assign(pixels, pixels + size_t(w) * size_t(h) * 4);
    stbi_image_free(pixels);
    return image;
}

} // namespace mfx::render
