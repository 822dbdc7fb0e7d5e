#include "render/exr_output.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <glm/gtc/packing.hpp>
#include <vector>

namespace mfx::render {

namespace {

// Little-endian bytes, as OpenEXR stores every number.
struct Bytes {
    std::vector<uint8_t> data;

    template <class T>
    void put(T value) {
        uint8_t raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T)); // the machines this runs on are little-endian
        data.insert(data.end(), raw, raw + sizeof(T));
    }
    void text(const char* s) { data.insert(data.end(), s, s + std::strlen(s) + 1); }
    void attribute(const char* name, const char* type, uint32_t size) {
        text(name);
        text(type);
        put(int32_t(size));
    }
};

uint16_t half(float v) {
    if (!std::isfinite(v)) v = 0.0f;
    return glm::packHalf1x16(std::clamp(v, -65504.0f, 65504.0f));
}

} // namespace

Status writeExr(const std::string& path, uint32_t width, uint32_t height,
                std::span<const float> rgba) {
    if (width == 0 || height == 0 || rgba.size() < size_t(width) * height * 4)
        return Error{path + ": no picture to write"};
    Bytes b;
    b.put(uint32_t(20000630));                     // magic number
    b.put(uint32_t(2));                            // version 2, single-part scanline
    const char* channels[] = {"A", "B", "G", "R"}; // alphabetical, as the file requires
    b.attribute("channels", "chlist", 4 * (2 + 16) + 1);
    for (const char* c : channels) {
        b.text(c);
        b.put(int32_t(1)); // HALF
        b.put(uint8_t(0)); // pLinear
        b.put(uint8_t(0));
        b.put(uint8_t(0));
        b.put(uint8_t(0));
        b.put(int32_t(1)); // xSampling
        b.put(int32_t(1)); // ySampling
    }
    b.put(uint8_t(0));
    b.attribute("compression", "compression", 1);
    b.put(uint8_t(0)); // NO_COMPRESSION
    for (const char* window : {"dataWindow", "displayWindow"}) {
        b.attribute(window, "box2i", 16);
        b.put(int32_t(0));
        b.put(int32_t(0));
        b.put(int32_t(width - 1));
        b.put(int32_t(height - 1));
    }
    b.attribute("lineOrder", "lineOrder", 1);
    b.put(uint8_t(0)); // INCREASING_Y
    b.attribute("pixelAspectRatio", "float", 4);
    b.put(1.0f);
    b.attribute("screenWindowCenter", "v2f", 8);
    b.put(0.0f);
    b.put(0.0f);
    b.attribute("screenWindowWidth", "float", 4);
    b.put(1.0f);
    b.put(uint8_t(0)); // end of the header

    // One scanline a block: y, byte count, then A, B, G and R of the line.
    const uint32_t lineBytes = width * 4 * 2;
    const uint64_t first = b.data.size() + uint64_t(height) * 8;
    for (uint32_t y = 0; y < height; ++y)
        b.put(uint64_t(first + uint64_t(y) * (8 + lineBytes)));
    const int order[] = {3, 2, 1, 0}; // A, B, G, R from RGBA
    for (uint32_t y = 0; y < height; ++y) {
        b.put(int32_t(y));
        b.put(int32_t(lineBytes));
        for (int c : order)
            for (uint32_t x = 0; x < width; ++x)
                b.put(half(rgba[(size_t(y) * width + x) * 4 + size_t(c)]));
    }
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(b.data.data()), std::streamsize(b.data.size()));
    if (!out) return Error{"cannot write " + path};
    return Ok{};
}

} // namespace mfx::render
