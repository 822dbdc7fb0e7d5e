// A second, deliberately plain reader of glTF 2.0 for tests: the JSON through nlohmann, buffers
// from a GLB's BIN chunk or base64 data URIs, accessors read element by element from their bytes.
// It shares no code with the importer (core/anim/gltf_import.cpp), so what the tests compute with
// it is an independent check. It also checks a document's structure (every accessor in bounds,
// counts consistent), as the tests of the exporter need. Trusted input only (files the tests wrote
// or the assets); failures are reported as gtest failures, not handled.
#pragma once

#include <cstdint>
#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace mfx::test {

struct RawGltf {
    nlohmann::json doc;
    std::vector<std::vector<unsigned char>> buffers;
};

inline std::vector<unsigned char> decodeBase64(const std::string& text) {
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        if (c == '+') return 62;
        if (c == '/') return 63;
        return -1;
    };
    std::vector<unsigned char> out;
    uint32_t bits = 0;
    int count = 0;
    for (char c : text) {
        const int v = value(c);
        if (v < 0) continue; // padding
        bits = (bits << 6) | uint32_t(v);
        count += 6;
        if (count >= 8) {
            count -= 8;
            out.push_back(static_cast<unsigned char>((bits >> count) & 0xFF));
        }
    }
    return out;
}

inline uint32_t readU32(const std::string& bytes, size_t offset) {
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + offset, 4);
    return value;
}

// Reads a .glb (checking its header and chunk layout) or a .gltf with data-URI buffers.
inline RawGltf readRawGltf(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    RawGltf raw;
    std::vector<unsigned char> bin;
    if (bytes.size() >= 12 && readU32(bytes, 0) == 0x46546C67) {
        EXPECT_EQ(readU32(bytes, 4), 2u) << "GLB version";
        EXPECT_EQ(readU32(bytes, 8), bytes.size()) << "GLB length";
        const uint32_t jsonLength = readU32(bytes, 12);
        EXPECT_EQ(readU32(bytes, 16), 0x4E4F534Au) << "first chunk is JSON";
        EXPECT_EQ(jsonLength % 4, 0u) << "JSON chunk padded to 4 bytes";
        raw.doc = nlohmann::json::parse(bytes.substr(20, jsonLength));
        const size_t binStart = 20 + size_t(jsonLength);
        if (binStart < bytes.size()) {
            const uint32_t binLength = readU32(bytes, binStart);
            EXPECT_EQ(readU32(bytes, binStart + 4), 0x004E4942u) << "second chunk is BIN";
            EXPECT_EQ(binLength % 4, 0u) << "BIN chunk padded to 4 bytes";
            EXPECT_EQ(binStart + 8 + binLength, bytes.size()) << "chunks fill the file";
            bin.assign(bytes.begin() + long(binStart + 8), bytes.end());
        }
    } else {
        raw.doc = nlohmann::json::parse(bytes);
    }
    for (const nlohmann::json& buffer : raw.doc.value("buffers", nlohmann::json::array())) {
        if (buffer.contains("uri")) {
            const std::string uri = buffer["uri"];
            const size_t comma = uri.find(',');
            EXPECT_EQ(uri.rfind("data:", 0), 0u) << "buffers are embedded";
            raw.buffers.push_back(decodeBase64(uri.substr(comma + 1)));
        } else {
            raw.buffers.push_back(bin);
        }
    }
    return raw;
}

inline size_t componentSize(int componentType) {
    switch (componentType) {
    case 5120:
    case 5121:
        return 1;
    case 5122:
    case 5123:
        return 2;
    case 5125:
    case 5126:
        return 4;
    default:
        return 0;
    }
}

inline size_t componentCount(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4") return 4;
    if (type == "MAT4") return 16;
    return 0;
}

// Accessor `index` as doubles, element by element (count × components), normalised integers
// mapped to [0, 1]. Checks that every byte read lies inside its view and its buffer.
inline std::vector<double> readAccessor(const RawGltf& raw, size_t index) {
    const nlohmann::json& accessor = raw.doc["accessors"].at(index);
    const nlohmann::json& view = raw.doc["bufferViews"].at(accessor["bufferView"].get<size_t>());
    const std::vector<unsigned char>& buffer = raw.buffers.at(view["buffer"].get<size_t>());
    const int type = accessor["componentType"];
    const size_t size = componentSize(type);
    const size_t components = componentCount(accessor["type"]);
    const size_t count = accessor["count"];
    const size_t viewOffset = view.value("byteOffset", size_t(0));
    const size_t viewLength = view["byteLength"];
    const size_t offset = accessor.value("byteOffset", size_t(0));
    const size_t stride = view.value("byteStride", size * components);
    const bool normalized = accessor.value("normalized", false);
    EXPECT_GT(size, 0u) << "accessors[" << index << "].componentType";
    EXPECT_GT(components, 0u) << "accessors[" << index << "].type";
    EXPECT_GE(count, 1u) << "accessors[" << index << "].count";
    EXPECT_EQ((viewOffset + offset) % size, 0u) << "accessors[" << index << "] aligned";
    EXPECT_LE(viewOffset + viewLength, buffer.size()) << "accessors[" << index << "] view";
    const size_t last = offset + (count - 1) * stride + size * components;
    EXPECT_LE(last, viewLength) << "accessors[" << index << "] inside its view";
    std::vector<double> out;
    if (last > viewLength || viewOffset + viewLength > buffer.size() || size == 0) return out;
    for (size_t e = 0; e < count; ++e)
        for (size_t c = 0; c < components; ++c) {
            const unsigned char* p = buffer.data() + viewOffset + offset + e * stride + c * size;
            double v = 0.0;
            switch (type) {
            case 5121:
                v = normalized ? p[0] / 255.0 : p[0];
                break;
            case 5123: {
                uint16_t u;
                std::memcpy(&u, p, 2);
                v = normalized ? u / 65535.0 : u;
                break;
            }
            case 5125: {
                uint32_t u;
                std::memcpy(&u, p, 4);
                v = u;
                break;
            }
            case 5126: {
                float f;
                std::memcpy(&f, p, 4);
                v = f;
                break;
            }
            default:
                ADD_FAILURE() << "componentType " << type << " not read by this helper";
            }
            out.push_back(v);
        }
    return out;
}

} // namespace mfx::test
