// glTF 2.0 import (policies in gltf_import.h). tinygltf parses the JSON and decodes the buffers;
// nothing it hands over is trusted: every index, byte range, format and number is checked here
// before it is used, against the glTF 2.0 specification (Khronos, 2021), sections 3.6 (buffers,
// views, accessors), 3.7 (meshes), 3.8 (skins), 3.11 (animations) and 4 (GLB).
//
// Errors are built as "element: what is wrong" and prefixed with the file's name once, at the top.
#include "core/anim/gltf_import.h"

#include "core/enum_names.h"
#include "core/json_shape.h"

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <queue>
#include <span>
#include <string>
#include <vector>

namespace mfx::anim {

namespace {

using Bytes = std::vector<unsigned char>;

std::string at(const std::string& array, size_t index) {
    return array + "[" + std::to_string(index) + "]";
}

std::string number(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", double(value));
    return text;
}

// --- Reading the file -----------------------------------------------------------------------

// tinygltf takes sizes as 32-bit unsigned; larger files are refused before they reach it.
constexpr uint64_t kMaxFileBytes = uint64_t(std::numeric_limits<int32_t>::max());

Result<Bytes> readBytes(const std::filesystem::path& path) {
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (error || !std::filesystem::exists(status))
        return Error{"cannot open the file (" +
                     (error ? error.message() : std::string("no such file")) + ")"};
    if (!std::filesystem::is_regular_file(status))
        return Error{"cannot open the file (not a regular file)"};
    const uint64_t size = std::filesystem::file_size(path, error);
    if (error) return Error{"cannot read the file (" + error.message() + ")"};
    if (size > kMaxFileBytes) return Error{"the file is larger than 2 GiB"};
    Bytes bytes(size);
    std::ifstream in(path, std::ios::binary);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
        return Error{"cannot read the file"};
    return bytes;
}

// --- tinygltf's file system and image hooks ----------------------------------------------------

// External buffers and images are looked up in the glTF file's folder only, and only there: a
// URI that leads out of it ("../../etc/passwd", "%2e%2e/", an absolute path, a link that points
// elsewhere) is refused. tinygltf would also try the working directory, which could silently
// pick up an unrelated file.
struct ExternalFiles {
    std::string directory;           // absolute, ends with '/': what tinygltf joins URIs to
    std::filesystem::path canonical; // the same folder with links and dots resolved
};

// Whether `path` names something strictly inside `folder` (canonical) once its links and dots
// are resolved.
bool insideFolder(const std::filesystem::path& folder, const std::filesystem::path& path) {
    std::error_code error;
    const std::filesystem::path resolved = std::filesystem::weakly_canonical(path, error);
    if (error || folder.empty()) return false;
    const auto [f, r] =
        std::mismatch(folder.begin(), folder.end(), resolved.begin(), resolved.end());
    return f == folder.end() && r != resolved.end();
}

bool externalFileExists(const std::string& path, void* user) {
    const auto* files = static_cast<const ExternalFiles*>(user);
    if (path.rfind(files->directory, 0) != 0 || path.find('\0') != std::string::npos ||
        !insideFolder(files->canonical, path))
        return false;
    std::error_code error;
    return std::filesystem::is_regular_file(path, error);
}

std::string keepPath(const std::string& path, void*) {
    return path;
}

// tinygltf's own reader sizes its buffer with tellg(), which is meaningless for directories and
// special files; this one reads regular files of bounded size only.
bool readExternalFile(Bytes* out, std::string* err, const std::string& path, void* user) {
    if (!externalFileExists(path, user)) {
        *err += "not a regular file inside the glTF file's folder";
        return false;
    }
    Result<Bytes> bytes = readBytes(path);
    if (!bytes) {
        *err += bytes.error().message;
        return false;
    }
    *out = std::move(bytes).value();
    return true;
}

bool refuseWrite(std::string* err, const std::string&, const Bytes&, void*) {
    *err += "writing is not supported";
    return false;
}

// Images are never needed: accept every image without decoding it.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int,
               const unsigned char*, int, void*) {
    return true;
}

// tinygltf's messages may span lines or quote a whole data URI: keep the first line, bounded,
// printable.
std::string firstLine(const std::string& text) {
    std::string line;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            if (line.empty()) continue;
            break;
        }
        line += (static_cast<unsigned char>(c) < 0x20) ? '?' : c;
    }
    constexpr size_t kMaxLength = 200;
    if (line.size() > kMaxLength) line = line.substr(0, kMaxLength) + "...";
    while (!line.empty() && (line.back() == ' ' || line.back() == '.'))
        line.pop_back();
    return line.empty() ? "the file is not valid glTF" : line;
}

// --- GLB container -----------------------------------------------------------------------------

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A; // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;  // "BIN\0"
constexpr size_t kGlbHeaderBytes = 12;
constexpr size_t kChunkHeaderBytes = 8;

uint32_t readU32(std::span<const unsigned char> bytes, size_t offset) {
    return uint32_t(bytes[offset]) | uint32_t(bytes[offset + 1]) << 8 |
           uint32_t(bytes[offset + 2]) << 16 | uint32_t(bytes[offset + 3]) << 24;
}

bool isGlb(std::span<const unsigned char> bytes) {
    return bytes.size() >= 4 && readU32(bytes, 0) == kGlbMagic;
}

struct GlbChunks {
    std::span<const unsigned char> json;
    std::span<const unsigned char> bin;
};

// Checks the header and every chunk's bounds (tinygltf trusts the chunk lengths), and returns the
// JSON chunk and the BIN chunk (empty when absent). Unknown chunks are skipped, as GLB asks.
Result<GlbChunks> splitGlb(std::span<const unsigned char> bytes) {
    if (bytes.size() < kGlbHeaderBytes)
        return Error{"GLB header is truncated (" + std::to_string(bytes.size()) + " bytes)"};
    const uint32_t version = readU32(bytes, 4);
    if (version != 2) return Error{"GLB version " + std::to_string(version) + " is not 2"};
    const uint32_t length = readU32(bytes, 8);
    if (length != bytes.size())
        return Error{"GLB header gives a length of " + std::to_string(length) +
                     " bytes, the file has " + std::to_string(bytes.size())};
    GlbChunks chunks;
    bool haveJson = false;
    bool haveBin = false;
    size_t offset = kGlbHeaderBytes;
    for (int chunk = 0; offset < bytes.size(); ++chunk) {
        const std::string where = "GLB chunk " + std::to_string(chunk);
        if (bytes.size() - offset < kChunkHeaderBytes)
            return Error{where + ": header is truncated"};
        const uint32_t chunkLength = readU32(bytes, offset);
        const uint32_t chunkType = readU32(bytes, offset + 4);
        const size_t dataStart = offset + kChunkHeaderBytes;
        if (chunkLength > bytes.size() - dataStart)
            return Error{where + ": " + std::to_string(chunkLength) + " bytes run past the end"};
        if (chunkLength % 4 != 0) return Error{where + ": length is not a multiple of 4"};
        const auto data = bytes.subspan(dataStart, chunkLength);
        if (chunk == 0 && chunkType != kChunkJson) return Error{where + ": is not the JSON chunk"};
        if (chunkType == kChunkJson) {
            if (haveJson) return Error{where + ": a second JSON chunk"};
            haveJson = true;
            chunks.json = data;
        } else if (chunkType == kChunkBin) {
            if (haveBin) return Error{where + ": a second BIN chunk"};
            if (chunk != 1) return Error{where + ": the BIN chunk must come right after JSON"};
            haveBin = true;
            chunks.bin = data;
        }
        offset = dataStart + chunkLength;
    }
    if (!haveJson) return Error{"GLB has no JSON chunk"};
    if (chunks.json.empty()) return Error{"GLB chunk 0: the JSON chunk is empty"};
    return chunks;
}

void appendU32(Bytes& out, uint32_t value) {
    for (int i = 0; i < 4; ++i)
        out.push_back(static_cast<unsigned char>(value >> (8 * i)));
}

// A GLB holding just the checked JSON and BIN chunks, laid out exactly as tinygltf expects.
Bytes rebuildGlb(const GlbChunks& chunks) {
    const bool withBin = !chunks.bin.empty();
    const size_t total = kGlbHeaderBytes + kChunkHeaderBytes + chunks.json.size() +
                         (withBin ? kChunkHeaderBytes + chunks.bin.size() : 0);
    Bytes out;
    out.reserve(total);
    appendU32(out, kGlbMagic);
    appendU32(out, 2);
    appendU32(out, uint32_t(total));
    appendU32(out, uint32_t(chunks.json.size()));
    appendU32(out, kChunkJson);
    out.insert(out.end(), chunks.json.begin(), chunks.json.end());
    if (withBin) {
        appendU32(out, uint32_t(chunks.bin.size()));
        appendU32(out, kChunkBin);
        out.insert(out.end(), chunks.bin.begin(), chunks.bin.end());
    }
    return out;
}

// --- The JSON's shape --------------------------------------------------------------------------

// tinygltf refuses a missing required property with a message that does not say which element
// lacks it; this pass finds those first and names the element. It checks only the shape that
// tinygltf relies on (required members and their JSON types); values are checked after parsing.
using Json = nlohmann::json;

enum class Kind { Unsigned, String, Array, Object };

Status require(const Json& object, const char* key, Kind kind, const std::string& where) {
    const auto it = object.find(key);
    const std::string name = where + "." + key;
    if (it == object.end()) return Error{name + ": missing"};
    switch (kind) {
    case Kind::Unsigned:
        if (!it->is_number_unsigned()) return Error{name + ": not a whole number >= 0"};
        break;
    case Kind::String:
        if (!it->is_string()) return Error{name + ": not a string"};
        break;
    case Kind::Array:
        if (!it->is_array()) return Error{name + ": not an array"};
        break;
    case Kind::Object:
        if (!it->is_object()) return Error{name + ": not an object"};
        break;
    }
    return Ok{};
}

struct Requirement {
    const char* key;
    Kind kind;
};

Status requireAll(const Json& object, std::initializer_list<Requirement> requirements,
                  const std::string& where) {
    if (!object.is_object()) return Error{where + ": not an object"};
    for (const Requirement& r : requirements)
        if (Status s = require(object, r.key, r.kind, where); !s) return s;
    return Ok{};
}

// Calls `check(element, "name[i]")` for each element of root[name] when it is there.
Status eachElement(const Json& root, const char* name,
                   const std::function<Status(const Json&, const std::string&)>& check) {
    const auto it = root.find(name);
    if (it == root.end()) return Ok{};
    if (!it->is_array()) return Error{std::string(name) + ": not an array"};
    for (size_t i = 0; i < it->size(); ++i)
        if (Status s = check((*it)[i], at(name, i)); !s) return s;
    return Ok{};
}

// A URI as tinygltf reads it: %XX decoded, '+' a space (glTF 2.0, 3.3: URIs are RFC 3986).
std::string decodeUri(const std::string& uri) {
    auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return 0;
    };
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            out += ' ';
        } else if (uri[i] == '%' && i + 2 < uri.size()) {
            out += char(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

// An external file's URI must stay inside `folder` (the glTF file's, canonical); data: URIs hold
// their bytes and are decoded by tinygltf.
Status checkUri(const Json& element, const std::string& where,
                const std::filesystem::path& folder) {
    const auto it = element.find("uri");
    if (it == element.end() || !it->is_string()) return Ok{};
    const std::string& uri = it->get_ref<const std::string&>();
    if (uri.rfind("data:", 0) == 0 && uri.find(";base64,") != std::string::npos) return Ok{};
    const std::string path = decodeUri(uri);
    if (path.empty()) return Error{where + ".uri: empty; give a file's name or a data: URI"};
    if (std::any_of(path.begin(), path.end(), [](char c) { return (unsigned char)(c) < 0x20; }))
        return Error{where + ".uri: holds a control character once decoded"};
    if (std::filesystem::path(path).is_absolute() || !insideFolder(folder, folder / path))
        return Error{where + ".uri: \"" + firstLine(uri) +
                     "\" leads outside the glTF file's folder; buffers and images must lie "
                     "inside it or be data: URIs"};
    return Ok{};
}

Status checkBufferShape(const Json& buffer, const std::string& where, bool glb,
                        const std::filesystem::path& folder) {
    if (Status s = requireAll(buffer, {{"byteLength", Kind::Unsigned}}, where); !s) return s;
    // Only a GLB's first buffer may leave out its URI: it is the BIN chunk.
    if (glb && where == "buffers[0]" && !buffer.contains("uri")) return Ok{};
    if (Status s = require(buffer, "uri", Kind::String, where); !s) return s;
    return checkUri(buffer, where, folder);
}

Status checkBufferViewShape(const Json& view, const std::string& where) {
    if (Status s =
            requireAll(view, {{"buffer", Kind::Unsigned}, {"byteLength", Kind::Unsigned}}, where);
        !s)
        return s;
    const auto stride = view.find("byteStride");
    if (stride == view.end()) return Ok{};
    const bool valid = stride->is_number_unsigned() && stride->get<uint64_t>() >= 4 &&
                       stride->get<uint64_t>() <= 252 && stride->get<uint64_t>() % 4 == 0;
    if (!valid)
        return Error{where + ".byteStride: " + firstLine(stride->dump()) +
                     " is not a multiple of 4 from 4 to 252"};
    return Ok{};
}

Status checkAccessorShape(const Json& accessor, const std::string& where) {
    if (Status s = requireAll(
            accessor,
            {{"componentType", Kind::Unsigned}, {"count", Kind::Unsigned}, {"type", Kind::String}},
            where);
        !s)
        return s;
    const auto sparse = accessor.find("sparse");
    if (sparse == accessor.end()) return Ok{};
    const std::string sparseWhere = where + ".sparse";
    if (Status s = requireAll(
            *sparse,
            {{"count", Kind::Unsigned}, {"indices", Kind::Object}, {"values", Kind::Object}},
            sparseWhere);
        !s)
        return s;
    if (Status s = requireAll((*sparse)["indices"],
                              {{"bufferView", Kind::Unsigned}, {"componentType", Kind::Unsigned}},
                              sparseWhere + ".indices");
        !s)
        return s;
    return requireAll((*sparse)["values"], {{"bufferView", Kind::Unsigned}},
                      sparseWhere + ".values");
}

// tinygltf also refuses, without naming the primitive, indices whose accessor is missing or has
// no bufferView.
Status checkIndicesShape(const Json& root, const Json& primitive, const std::string& where) {
    const auto indices = primitive.find("indices");
    if (indices == primitive.end()) return Ok{};
    const Json* accessors = root.contains("accessors") ? &root["accessors"] : nullptr;
    if (!indices->is_number_unsigned() || !accessors ||
        indices->get<uint64_t>() >= accessors->size())
        return Error{where + ".indices: accessor " + firstLine(indices->dump()) +
                     " does not exist"};
    const size_t accessor = indices->get<size_t>();
    if (!(*accessors)[accessor].contains("bufferView"))
        return Error{where + ".indices: " + at("accessors", accessor) +
                     " has no bufferView, which indices need"};
    return Ok{};
}

Status checkMeshShape(const Json& root, const Json& mesh, const std::string& where) {
    if (Status s = requireAll(mesh, {{"primitives", Kind::Array}}, where); !s) return s;
    return eachElement(mesh, "primitives", [&](const Json& primitive, const std::string& name) {
        const std::string primitiveWhere = where + "." + name;
        if (Status s = requireAll(primitive, {{"attributes", Kind::Object}}, primitiveWhere); !s)
            return s;
        return checkIndicesShape(root, primitive, primitiveWhere);
    });
}

Status checkAnimationShape(const Json& animation, const std::string& where) {
    if (Status s =
            requireAll(animation, {{"channels", Kind::Array}, {"samplers", Kind::Array}}, where);
        !s)
        return s;
    Status channels =
        eachElement(animation, "channels", [&](const Json& channel, const std::string& name) {
            const std::string channelWhere = where + "." + name;
            if (Status s = requireAll(
                    channel, {{"sampler", Kind::Unsigned}, {"target", Kind::Object}}, channelWhere);
                !s)
                return s;
            return requireAll(channel["target"], {{"path", Kind::String}},
                              channelWhere + ".target");
        });
    if (!channels) return channels;
    return eachElement(animation, "samplers", [&](const Json& sampler, const std::string& name) {
        return requireAll(sampler, {{"input", Kind::Unsigned}, {"output", Kind::Unsigned}},
                          where + "." + name);
    });
}

// Far deeper than any glTF document needs (the schema itself nests about eight levels), and more
// values than a real file's JSON holds (its bulk data is in buffers): each value becomes a node in
// nlohmann's tree and again in tinygltf's structs, hundreds of bytes each.
constexpr JsonLimits kGltfJsonLimits{64, size_t(1) << 20};

Status checkGltfJson(std::span<const unsigned char> text, bool glb,
                     const std::filesystem::path& folder) {
    // tinygltf converts `extras` recursively: deep nesting would overflow its stack.
    if (Status shape = checkJsonShape(text, kGltfJsonLimits); !shape) return shape;
    Json root;
    try {
        root = Json::parse(text.begin(), text.end());
    } catch (const Json::exception& e) {
        // e.what() starts with "[json.exception.parse_error.101] "; the rest is the reason.
        std::string reason = e.what();
        if (const size_t end = reason.find("] "); end != std::string::npos)
            reason = reason.substr(end + 2);
        const bool looksLikeJson =
            !text.empty() && (text[0] == '{' || text[0] == ' ' || text[0] == '\n' ||
                              text[0] == '\r' || text[0] == '\t' || text[0] == 0xEF);
        if (glb || looksLikeJson) return Error{"not valid JSON (" + firstLine(reason) + ")"};
        // Not JSON at all: the parser's reason would quote the file's first bytes (a file that is
        // not the user's own, named by a scene, should not be echoed).
        return Error{"neither a GLB file (no 'glTF' magic) nor glTF JSON"};
    }
    if (!root.is_object()) return Error{"the JSON is not an object"};
    if (Status s = requireAll(root, {{"asset", Kind::Object}}, "glTF"); !s)
        return Error{"asset: missing or not an object"};
    if (Status s = require(root["asset"], "version", Kind::String, "asset"); !s) return s;
    const std::pair<const char*, std::function<Status(const Json&, const std::string&)>> arrays[] =
        {
            {"buffers", [&](const Json& e,
                            const std::string& w) { return checkBufferShape(e, w, glb, folder); }},
            {"images", [&](const Json& e, const std::string& w) { return checkUri(e, w, folder); }},
            {"bufferViews", &checkBufferViewShape},
            {"accessors", &checkAccessorShape},
            {"meshes",
             [&](const Json& e, const std::string& w) { return checkMeshShape(root, e, w); }},
            {"nodes", [](const Json& e, const std::string& w) { return requireAll(e, {}, w); }},
            {"skins",
             [](const Json& e, const std::string& w) {
                 return requireAll(e, {{"joints", Kind::Array}}, w);
             }},
            {"animations", &checkAnimationShape},
        };
    for (const auto& [name, check] : arrays)
        if (Status s = eachElement(root, name, check); !s) return s;
    return Ok{};
}

// --- Parsing with tinygltf ---------------------------------------------------------------------

Result<tinygltf::Model> parseModel(const Bytes& bytes, const std::filesystem::path& file) {
    std::error_code error;
    std::filesystem::path directory = std::filesystem::absolute(file, error).parent_path();
    ExternalFiles files{directory.string(), std::filesystem::weakly_canonical(directory, error)};
    if (files.directory.empty() || files.directory.back() != '/') files.directory += '/';

    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&skipImage, nullptr);
    loader.SetFsCallbacks(
        {&externalFileExists, &keepPath, &readExternalFile, &refuseWrite, &files});
    tinygltf::Model model;
    std::string err;
    std::string warn;
    bool loaded = false;
    if (isGlb(bytes)) {
        Result<GlbChunks> chunks = splitGlb(bytes);
        if (!chunks) return chunks.error();
        if (Status s = checkGltfJson(chunks.value().json, true, files.canonical); !s)
            return s.error();
        const Bytes glb = rebuildGlb(chunks.value());
        loaded = loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), unsigned(glb.size()),
                                             files.directory);
    } else {
        if (bytes.empty()) return Error{"the file is empty"};
        if (Status s = checkGltfJson(bytes, false, files.canonical); !s) return s.error();
        loaded = loader.LoadASCIIFromString(&model, &err, &warn,
                                            reinterpret_cast<const char*>(bytes.data()),
                                            unsigned(bytes.size()), files.directory);
    }
    if (!loaded) return Error{firstLine(err)};
    return model;
}

// --- Accessors ---------------------------------------------------------------------------------

// The component types glTF 2.0 allows (INT and DOUBLE are not among them); 0 for any other.
size_t componentBytes(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return 4;
    default:
        return 0;
    }
}

const char* componentName(int componentType) {
    static constexpr NamedValue<int> kNames[] = {
        {TINYGLTF_COMPONENT_TYPE_BYTE, "byte"},
        {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, "unsigned byte"},
        {TINYGLTF_COMPONENT_TYPE_SHORT, "short"},
        {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, "unsigned short"},
        {TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, "unsigned int"},
        {TINYGLTF_COMPONENT_TYPE_FLOAT, "float"}};
    return nameOf(componentType, kNames, "an invalid component type");
}

int componentsOf(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return 1;
    case TINYGLTF_TYPE_VEC2:
        return 2;
    case TINYGLTF_TYPE_VEC3:
        return 3;
    case TINYGLTF_TYPE_VEC4:
        return 4;
    case TINYGLTF_TYPE_MAT4:
        return 16;
    default:
        return 0; // MAT2 and MAT3 are never read
    }
}

const char* typeName(int type) {
    static constexpr NamedValue<int> kNames[] = {
        {TINYGLTF_TYPE_SCALAR, "SCALAR"}, {TINYGLTF_TYPE_VEC2, "VEC2"},
        {TINYGLTF_TYPE_VEC3, "VEC3"},     {TINYGLTF_TYPE_VEC4, "VEC4"},
        {TINYGLTF_TYPE_MAT2, "MAT2"},     {TINYGLTF_TYPE_MAT3, "MAT3"},
        {TINYGLTF_TYPE_MAT4, "MAT4"}};
    return nameOf(type, kNames, "an invalid type");
}

// The formats one use of an accessor accepts (glTF 2.0, 3.7.2.1 and 3.11 list them).
struct Format {
    int type = TINYGLTF_TYPE_SCALAR;
    bool floats = false;             // FLOAT
    bool unsignedNormalized = false; // normalised UNSIGNED_BYTE / UNSIGNED_SHORT
    bool signedNormalized = false;   // normalised BYTE / SHORT
    bool smallUnsigned = false;      // UNSIGNED_BYTE / UNSIGNED_SHORT
    bool unsignedInt = false;        // UNSIGNED_INT
};

bool accepts(const Format& format, int componentType, bool normalized) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return format.floats && !normalized;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return normalized ? format.unsignedNormalized : format.smallUnsigned;
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_SHORT:
        return normalized && format.signedNormalized;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return format.unsignedInt && !normalized;
    default:
        return false;
    }
}

// Without a bufferView an accessor is all zeros and nothing bounds its count but this.
constexpr size_t kMaxZeroAccessorCount = size_t(1) << 24;

// A checked window onto an accessor's elements: element i starts at data + i * stride, and every
// element lies inside its buffer view and buffer.
struct AccessorData {
    const unsigned char* data = nullptr; // nullptr: no bufferView, every element reads as zero
    size_t count = 0;
    size_t stride = 0;
    int componentType = 0;
    int components = 0;
    bool normalized = false;

    float component(size_t element, int index) const;
    uint32_t integer(size_t element, int index) const;
};

template <typename T>
T load(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof value); // views need not be aligned for T
    return value;
}

float AccessorData::component(size_t element, int index) const {
    if (!data) return 0.0f;
    const unsigned char* p =
        data + element * stride + size_t(index) * componentBytes(componentType);
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return float(*p) / (normalized ? 255.0f : 1.0f);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return float(load<uint16_t>(p)) / (normalized ? 65535.0f : 1.0f);
    case TINYGLTF_COMPONENT_TYPE_BYTE:
        return std::max(float(load<int8_t>(p)) / 127.0f, -1.0f);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
        return std::max(float(load<int16_t>(p)) / 32767.0f, -1.0f);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return float(load<uint32_t>(p));
    default:
        return 0.0f;
    }
}

uint32_t AccessorData::integer(size_t element, int index) const {
    if (!data) return 0;
    const unsigned char* p =
        data + element * stride + size_t(index) * componentBytes(componentType);
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return *p;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return load<uint16_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return load<uint32_t>(p);
    default:
        return 0;
    }
}

// Whether `count` elements of `elementBytes`, `stride` apart from `offset`, end within `length`
// bytes; written so that no intermediate value can overflow.
bool fitsIn(uint64_t offset, uint64_t count, uint64_t stride, uint64_t elementBytes,
            uint64_t length) {
    if (offset > length) return false;
    if (count == 0) return true;
    const uint64_t room = length - offset;
    if (elementBytes > room) return false;
    return (count - 1) <= (room - elementBytes) / stride;
}

// What one file may make the importer produce, in total. glTF lets a file of a kilobyte ask for
// any amount: an accessor without a bufferView is that many zeros, a mesh is copied once for each
// node that instances it, a sampler's key times once for each channel that uses it. Each is
// bounded on its own; this bounds their sum. A refusal names the element that passes a limit and
// the limit. The limits are far beyond a game character (tens of thousands of vertices, a few MB)
// and keep an import under about 1 GB however the file is built.
struct ImportBudget {
    static constexpr uint64_t kMaxElements = uint64_t(1) << 25; // accessor elements read
    static constexpr uint64_t kMaxVertices = uint64_t(1) << 22; // mesh vertices, copies included
    static constexpr uint64_t kMaxBytes = uint64_t(768) << 20;  // bytes of what is read and made

    uint64_t elements = 0;
    uint64_t vertices = 0;
    uint64_t bytes = 0;

    Status spend(const std::string& where, uint64_t moreElements, uint64_t moreVertices,
                 uint64_t moreBytes) {
        elements += moreElements;
        vertices += moreVertices;
        bytes += moreBytes;
        if (elements > kMaxElements)
            return Error{where + ": the file's accessors hold more than " +
                         std::to_string(kMaxElements) + " elements in all (the import's limit)"};
        if (vertices > kMaxVertices)
            return Error{where +
                         ": the file's meshes (a copy for each node using one) hold more "
                         "than " +
                         std::to_string(kMaxVertices) + " vertices in all (the import's limit)"};
        if (bytes > kMaxBytes)
            return Error{where + ": the import would make more than " +
                         std::to_string(kMaxBytes >> 20) + " MiB of data (the import's limit)"};
        return Ok{};
    }
};

// Opens accessor `index` and charges `budget` for its elements, read as `elementBytes` each.
Result<AccessorData> openAccessor(const tinygltf::Model& model, int index, const std::string& where,
                                  const Format& format, ImportBudget& budget,
                                  size_t elementBytesRead) {
    if (index < 0 || size_t(index) >= model.accessors.size())
        return Error{where + ": accessor " + std::to_string(index) + " does not exist"};
    const tinygltf::Accessor& accessor = model.accessors[size_t(index)];
    const std::string name = where + ": " + at("accessors", size_t(index));
    if (accessor.sparse.isSparse) return Error{name + " is sparse, which is not supported"};
    const int components = componentsOf(accessor.type);
    if (accessor.type != format.type ||
        !accepts(format, accessor.componentType, accessor.normalized))
        return Error{name + " holds " + typeName(accessor.type) + " of " +
                     (accessor.normalized ? "normalised " : "") +
                     componentName(accessor.componentType) + ", not a format allowed here"};
    if (accessor.count == 0) return Error{name + " has no elements"};
    if (Status s =
            budget.spend(name, accessor.count, 0, uint64_t(accessor.count) * elementBytesRead);
        !s)
        return s.error();

    AccessorData view;
    view.count = accessor.count;
    view.componentType = accessor.componentType;
    view.components = components;
    view.normalized = accessor.normalized;
    const size_t elementBytes = size_t(components) * componentBytes(accessor.componentType);
    if (accessor.bufferView < 0) {
        if (accessor.count > kMaxZeroAccessorCount)
            return Error{name + ": " + std::to_string(accessor.count) +
                         " elements without a bufferView is too many"};
        view.stride = elementBytes;
        return view;
    }
    if (size_t(accessor.bufferView) >= model.bufferViews.size())
        return Error{name + ": bufferView " + std::to_string(accessor.bufferView) +
                     " does not exist"};
    const tinygltf::BufferView& bufferView = model.bufferViews[size_t(accessor.bufferView)];
    const std::string viewName = at("bufferViews", size_t(accessor.bufferView));
    if (bufferView.buffer < 0 || size_t(bufferView.buffer) >= model.buffers.size())
        return Error{name + ": " + viewName + ": buffer " + std::to_string(bufferView.buffer) +
                     " does not exist"};
    const tinygltf::Buffer& buffer = model.buffers[size_t(bufferView.buffer)];
    if (!fitsIn(bufferView.byteOffset, 1, 1, bufferView.byteLength, buffer.data.size()))
        return Error{name + ": " + viewName + ": " + std::to_string(bufferView.byteLength) +
                     " bytes from byte " + std::to_string(bufferView.byteOffset) +
                     " run past the end of " + at("buffers", size_t(bufferView.buffer)) + " (" +
                     std::to_string(buffer.data.size()) + " bytes)"};
    view.stride = bufferView.byteStride == 0 ? elementBytes : bufferView.byteStride;
    if (view.stride < elementBytes)
        return Error{name + ": " + viewName + ": byteStride " + std::to_string(view.stride) +
                     " is smaller than an element (" + std::to_string(elementBytes) + " bytes)"};
    if (!fitsIn(accessor.byteOffset, accessor.count, view.stride, elementBytes,
                bufferView.byteLength))
        return Error{name + ": " + std::to_string(accessor.count) + " elements from byte " +
                     std::to_string(accessor.byteOffset) + " run past the end of " + viewName +
                     " (" + std::to_string(bufferView.byteLength) + " bytes)"};
    view.data = buffer.data.data() + bufferView.byteOffset + accessor.byteOffset;
    return view;
}

bool finite(const glm::vec4& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

// Every element as a vec4 (components past the type's are 0); NaN and infinities refused.
Result<std::vector<glm::vec4>> readFloats(const tinygltf::Model& model, int index,
                                          const std::string& where, const Format& format,
                                          ImportBudget& budget) {
    Result<AccessorData> opened =
        openAccessor(model, index, where, format, budget, sizeof(glm::vec4));
    if (!opened) return opened.error();
    const AccessorData& data = opened.value();
    std::vector<glm::vec4> values(data.count, glm::vec4(0.0f));
    for (size_t i = 0; i < data.count; ++i) {
        for (int c = 0; c < std::min(data.components, 4); ++c)
            values[i][c] = data.component(i, c);
        if (!finite(values[i]))
            return Error{where + ": element " + std::to_string(i) + " is not finite"};
    }
    return values;
}

Result<std::vector<glm::uvec4>> readIntegers(const tinygltf::Model& model, int index,
                                             const std::string& where, const Format& format,
                                             ImportBudget& budget) {
    Result<AccessorData> opened =
        openAccessor(model, index, where, format, budget, sizeof(glm::uvec4));
    if (!opened) return opened.error();
    const AccessorData& data = opened.value();
    std::vector<glm::uvec4> values(data.count, glm::uvec4(0));
    for (size_t i = 0; i < data.count; ++i)
        for (int c = 0; c < std::min(data.components, 4); ++c)
            values[i][c] = data.integer(i, c);
    return values;
}

Result<std::vector<glm::mat4>> readMatrices(const tinygltf::Model& model, int index,
                                            const std::string& where, ImportBudget& budget) {
    Format format{TINYGLTF_TYPE_MAT4};
    format.floats = true;
    Result<AccessorData> opened =
        openAccessor(model, index, where, format, budget, sizeof(glm::mat4));
    if (!opened) return opened.error();
    const AccessorData& data = opened.value();
    std::vector<glm::mat4> matrices(data.count);
    for (size_t i = 0; i < data.count; ++i)
        for (int c = 0; c < 16; ++c) {
            const float value = data.component(i, c);
            if (!std::isfinite(value))
                return Error{where + ": matrix " + std::to_string(i) + " is not finite"};
            matrices[i][c / 4][c % 4] = value; // column-major, as glTF stores them
        }
    return matrices;
}

Format floatFormat(int type) {
    Format format{type};
    format.floats = true;
    return format;
}

// --- Nodes -------------------------------------------------------------------------------------

struct NodeOrder {
    std::vector<int> parent;   // file index of each file node's parent, -1 for roots
    std::vector<int> order;    // file indices, parents first
    std::vector<int> newIndex; // file index -> index in Character::nodes
};

// Parents come first; otherwise the file's order is kept (a smallest-index-first topological
// order), so a file already in that order keeps its indices.
Result<NodeOrder> orderNodes(const tinygltf::Model& model) {
    const size_t count = model.nodes.size();
    NodeOrder result;
    result.parent.assign(count, -1);
    for (size_t i = 0; i < count; ++i) {
        for (int child : model.nodes[i].children) {
            const std::string where = at("nodes", i) + ".children";
            if (child < 0 || size_t(child) >= count)
                return Error{where + ": node " + std::to_string(child) + " does not exist"};
            if (size_t(child) == i) return Error{where + ": the node is its own child"};
            const int previous = result.parent[size_t(child)];
            if (previous == int(i))
                return Error{where + ": node " + std::to_string(child) + " is listed twice"};
            if (previous >= 0)
                return Error{at("nodes", size_t(child)) + ": child of both " +
                             at("nodes", size_t(previous)) + " and " + at("nodes", i)};
            result.parent[size_t(child)] = int(i);
        }
    }
    std::priority_queue<int, std::vector<int>, std::greater<int>> ready;
    for (size_t i = 0; i < count; ++i)
        if (result.parent[i] < 0) ready.push(int(i));
    result.newIndex.assign(count, -1);
    while (!ready.empty()) {
        const int node = ready.top();
        ready.pop();
        result.newIndex[size_t(node)] = int(result.order.size());
        result.order.push_back(node);
        for (int child : model.nodes[size_t(node)].children)
            ready.push(child);
    }
    if (result.order.size() != count) {
        for (size_t i = 0; i < count; ++i)
            if (result.newIndex[i] < 0)
                return Error{at("nodes", i) + ": the node hierarchy has a cycle through it"};
    }
    return result;
}

// A node matrix as translation, rotation and scale (glTF requires matrices to be decomposable).
// A mirroring matrix gets a negative x scale; with a zero scale the rotation is undefined and
// taken as identity.
Transform decompose(const glm::mat4& m) {
    Transform t;
    t.translation = glm::vec3(m[3]);
    const glm::vec3 axes[3] = {glm::vec3(m[0]), glm::vec3(m[1]), glm::vec3(m[2])};
    t.scale = glm::vec3(glm::length(axes[0]), glm::length(axes[1]), glm::length(axes[2]));
    if (glm::determinant(glm::mat3(m)) < 0.0f) t.scale.x = -t.scale.x;
    if (t.scale.x == 0.0f || t.scale.y == 0.0f || t.scale.z == 0.0f) return t;
    const glm::mat3 rotation(axes[0] / t.scale.x, axes[1] / t.scale.y, axes[2] / t.scale.z);
    t.rotation = glm::normalize(glm::quat_cast(rotation));
    return t;
}

Result<std::vector<float>> numbers(const std::vector<double>& values, size_t expected,
                                   const std::string& where) {
    if (values.size() != expected)
        return Error{where + ": " + std::to_string(values.size()) + " numbers, expected " +
                     std::to_string(expected)};
    std::vector<float> out(expected);
    for (size_t i = 0; i < expected; ++i) {
        out[i] = float(values[i]);
        if (!std::isfinite(out[i]))
            return Error{where + ": number " + std::to_string(i) + " is not a finite float"};
    }
    return out;
}

Result<Transform> nodeTransform(const tinygltf::Node& node, const std::string& where) {
    Transform t;
    if (!node.matrix.empty()) {
        Result<std::vector<float>> m = numbers(node.matrix, 16, where + ".matrix");
        if (!m) return m.error();
        glm::mat4 matrix;
        for (int i = 0; i < 16; ++i)
            matrix[i / 4][i % 4] = m.value()[size_t(i)];
        t = decompose(matrix);
        if (!std::isfinite(t.scale.x) || !std::isfinite(t.scale.y) || !std::isfinite(t.scale.z))
            return Error{where + ".matrix: cannot be split into translation, rotation, scale"};
        return t;
    }
    if (!node.translation.empty()) {
        Result<std::vector<float>> v = numbers(node.translation, 3, where + ".translation");
        if (!v) return v.error();
        t.translation = glm::vec3(v.value()[0], v.value()[1], v.value()[2]);
    }
    if (!node.rotation.empty()) {
        Result<std::vector<float>> q = numbers(node.rotation, 4, where + ".rotation");
        if (!q) return q.error();
        const glm::quat rotation(q.value()[3], q.value()[0], q.value()[1], q.value()[2]);
        const float length = glm::length(rotation);
        if (!(length > 0.0f) || !std::isfinite(length))
            return Error{where + ".rotation: not a rotation (zero quaternion)"};
        t.rotation = rotation / length;
    }
    if (!node.scale.empty()) {
        Result<std::vector<float>> s = numbers(node.scale, 3, where + ".scale");
        if (!s) return s.error();
        t.scale = glm::vec3(s.value()[0], s.value()[1], s.value()[2]);
    }
    return t;
}

Status readNodes(const tinygltf::Model& model, const NodeOrder& order, Character& character,
                 ImportBudget&) {
    for (int fileIndex : order.order) {
        const tinygltf::Node& source = model.nodes[size_t(fileIndex)];
        const std::string where = at("nodes", size_t(fileIndex));
        Node node;
        node.name = source.name.empty() ? "node_" + std::to_string(fileIndex) : source.name;
        const int parent = order.parent[size_t(fileIndex)];
        node.parent = parent < 0 ? -1 : order.newIndex[size_t(parent)];
        Result<Transform> rest = nodeTransform(source, where);
        if (!rest) return rest.error();
        node.rest = rest.value();
        if (source.mesh >= 0 && size_t(source.mesh) >= model.meshes.size())
            return Error{where + ".mesh: mesh " + std::to_string(source.mesh) + " does not exist"};
        if (source.skin >= 0 && size_t(source.skin) >= model.skins.size())
            return Error{where + ".skin: skin " + std::to_string(source.skin) + " does not exist"};
        character.nodes.push_back(std::move(node));
    }
    return Ok{};
}

// --- Skins -------------------------------------------------------------------------------------

Status readSkins(const tinygltf::Model& model, const NodeOrder& order, Character& character,
                 ImportBudget& budget) {
    for (size_t s = 0; s < model.skins.size(); ++s) {
        const tinygltf::Skin& source = model.skins[s];
        const std::string where = at("skins", s);
        Skin skin;
        skin.name = source.name.empty() ? "skin_" + std::to_string(s) : source.name;
        if (source.joints.empty()) return Error{where + ".joints: no joints"};
        for (size_t j = 0; j < source.joints.size(); ++j) {
            const int joint = source.joints[j];
            if (joint < 0 || size_t(joint) >= model.nodes.size())
                return Error{at(where + ".joints", j) + ": node " + std::to_string(joint) +
                             " does not exist"};
            skin.joints.push_back(order.newIndex[size_t(joint)]);
        }
        if (source.inverseBindMatrices < 0) {
            skin.inverseBind.assign(skin.joints.size(), glm::mat4(1.0f));
        } else {
            const std::string ibmWhere = where + ".inverseBindMatrices";
            Result<std::vector<glm::mat4>> matrices =
                readMatrices(model, source.inverseBindMatrices, ibmWhere, budget);
            if (!matrices) return matrices.error();
            if (matrices.value().size() != skin.joints.size())
                return Error{ibmWhere + ": " + std::to_string(matrices.value().size()) +
                             " matrices for " + std::to_string(skin.joints.size()) + " joints"};
            skin.inverseBind = std::move(matrices).value();
        }
        character.skins.push_back(std::move(skin));
    }
    return Ok{};
}

// --- Meshes ------------------------------------------------------------------------------------

// Unit normals everywhere: the file's where it has usable ones, else the smooth normal, else +z
// for a vertex on no triangle of any area.
void completeNormals(Primitive& primitive) {
    std::vector<glm::vec3> smooth;
    primitive.normals.resize(primitive.positions.size(), glm::vec3(0.0f));
    for (size_t v = 0; v < primitive.normals.size(); ++v) {
        glm::vec3& n = primitive.normals[v];
        const float length = glm::length(n);
        if (length > 1e-12f && std::isfinite(length)) {
            n /= length;
            continue;
        }
        if (smooth.empty())
            smooth = smoothNormals(primitive.positions, primitive.indices, glm::vec3(0, 0, 1));
        n = smooth[v];
    }
}

using Attributes = std::map<std::string, int>;

const int* findAttribute(const Attributes& attributes, const char* semantic) {
    auto it = attributes.find(semantic);
    return it == attributes.end() ? nullptr : &it->second;
}

Status sameCount(size_t count, size_t vertices, const std::string& where) {
    if (count == vertices) return Ok{};
    return Error{where + ": " + std::to_string(count) + " elements for " +
                 std::to_string(vertices) + " vertices"};
}

// Weights renormalised to sum to 1; all-zero weights bind the vertex to joint 0.
Status readSkinWeights(const tinygltf::Model& model, const Attributes& attributes,
                       const std::string& where, Primitive& primitive, ImportBudget& budget) {
    const int* joints = findAttribute(attributes, "JOINTS_0");
    const int* weights = findAttribute(attributes, "WEIGHTS_0");
    if (!joints && !weights) return Ok{};
    if (!joints || !weights)
        return Error{where + ".attributes: " +
                     (joints ? "JOINTS_0 without WEIGHTS_0" : "WEIGHTS_0 without JOINTS_0")};
    Format jointFormat{TINYGLTF_TYPE_VEC4};
    jointFormat.smallUnsigned = true;
    Result<std::vector<glm::uvec4>> jointValues =
        readIntegers(model, *joints, where + ".attributes.JOINTS_0", jointFormat, budget);
    if (!jointValues) return jointValues.error();
    Format weightFormat = floatFormat(TINYGLTF_TYPE_VEC4);
    weightFormat.unsignedNormalized = true;
    Result<std::vector<glm::vec4>> weightValues =
        readFloats(model, *weights, where + ".attributes.WEIGHTS_0", weightFormat, budget);
    if (!weightValues) return weightValues.error();
    const size_t vertices = primitive.positions.size();
    for (auto [count, name] : {std::pair{jointValues.value().size(), "JOINTS_0"},
                               std::pair{weightValues.value().size(), "WEIGHTS_0"}})
        if (Status s = sameCount(count, vertices, where + ".attributes." + name); !s) return s;
    primitive.joints = std::move(jointValues).value();
    primitive.weights = std::move(weightValues).value();
    for (size_t v = 0; v < vertices; ++v) {
        glm::vec4& w = primitive.weights[v];
        if (w.x < 0.0f || w.y < 0.0f || w.z < 0.0f || w.w < 0.0f)
            return Error{where + ".attributes.WEIGHTS_0: vertex " + std::to_string(v) +
                         " has a negative weight"};
        const float sum = w.x + w.y + w.z + w.w;
        if (sum > 0.0f) {
            w /= sum;
        } else {
            w = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
            primitive.joints[v] = glm::uvec4(0);
        }
    }
    return Ok{};
}

Status readIndices(const tinygltf::Model& model, int accessor, const std::string& where,
                   Primitive& primitive, ImportBudget& budget) {
    const size_t vertices = primitive.positions.size();
    if (accessor < 0) {
        if (vertices % 3 != 0)
            return Error{where + ": " + std::to_string(vertices) +
                         " vertices without indices are not whole triangles"};
        if (vertices > std::numeric_limits<uint32_t>::max())
            return Error{where + ": too many vertices"};
        primitive.indices.resize(vertices);
        std::iota(primitive.indices.begin(), primitive.indices.end(), 0u);
        return Ok{};
    }
    Format format{TINYGLTF_TYPE_SCALAR};
    format.smallUnsigned = true;
    format.unsignedInt = true;
    const std::string indicesWhere = where + ".indices";
    Result<std::vector<glm::uvec4>> values =
        readIntegers(model, accessor, indicesWhere, format, budget);
    if (!values) return values.error();
    if (values.value().size() % 3 != 0)
        return Error{indicesWhere + ": " + std::to_string(values.value().size()) +
                     " indices are not whole triangles"};
    primitive.indices.reserve(values.value().size());
    for (const glm::uvec4& value : values.value()) {
        if (value.x >= vertices)
            return Error{indicesWhere + ": index " + std::to_string(value.x) +
                         " >= " + std::to_string(vertices) + " vertices"};
        primitive.indices.push_back(value.x);
    }
    return Ok{};
}

Result<glm::vec4> baseColor(const tinygltf::Model& model, int material, const std::string& where) {
    if (material < 0) return glm::vec4(1.0f);
    if (size_t(material) >= model.materials.size())
        return Error{where + ".material: material " + std::to_string(material) + " does not exist"};
    const std::string factorWhere =
        at("materials", size_t(material)) + ".pbrMetallicRoughness.baseColorFactor";
    Result<std::vector<float>> factor = numbers(
        model.materials[size_t(material)].pbrMetallicRoughness.baseColorFactor, 4, factorWhere);
    if (!factor) return factor.error();
    return glm::vec4(factor.value()[0], factor.value()[1], factor.value()[2], factor.value()[3]);
}

Result<Primitive> readPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& source,
                                const std::string& where, ImportBudget& budget) {
    Primitive primitive;
    const Attributes& attributes = source.attributes;
    const int* position = findAttribute(attributes, "POSITION");
    if (!position) return Error{where + ".attributes: no POSITION"};
    Result<std::vector<glm::vec4>> positions = readFloats(
        model, *position, where + ".attributes.POSITION", floatFormat(TINYGLTF_TYPE_VEC3), budget);
    if (!positions) return positions.error();
    for (const glm::vec4& p : positions.value())
        primitive.positions.emplace_back(p);
    const size_t vertices = primitive.positions.size();

    if (const int* normal = findAttribute(attributes, "NORMAL")) {
        const std::string normalWhere = where + ".attributes.NORMAL";
        Result<std::vector<glm::vec4>> normals =
            readFloats(model, *normal, normalWhere, floatFormat(TINYGLTF_TYPE_VEC3), budget);
        if (!normals) return normals.error();
        if (Status s = sameCount(normals.value().size(), vertices, normalWhere); !s)
            return s.error();
        for (const glm::vec4& n : normals.value())
            primitive.normals.emplace_back(n);
    }
    if (const int* uv = findAttribute(attributes, "TEXCOORD_0")) {
        const std::string uvWhere = where + ".attributes.TEXCOORD_0";
        Format format = floatFormat(TINYGLTF_TYPE_VEC2);
        format.unsignedNormalized = true;
        Result<std::vector<glm::vec4>> uvs = readFloats(model, *uv, uvWhere, format, budget);
        if (!uvs) return uvs.error();
        if (Status s = sameCount(uvs.value().size(), vertices, uvWhere); !s) return s.error();
        for (const glm::vec4& t : uvs.value())
            primitive.uvs.emplace_back(t);
    }
    if (Status s = readSkinWeights(model, attributes, where, primitive, budget); !s)
        return s.error();
    if (Status s = readIndices(model, source.indices, where, primitive, budget); !s)
        return s.error();
    completeNormals(primitive);
    Result<glm::vec4> color = baseColor(model, source.material, where);
    if (!color) return color.error();
    primitive.baseColor = color.value();
    return primitive;
}

// The bytes a primitive's arrays and struct take.
uint64_t primitiveBytes(const Primitive& p) {
    return sizeof(Primitive) + p.positions.size() * sizeof(glm::vec3) +
           p.normals.size() * sizeof(glm::vec3) + p.uvs.size() * sizeof(glm::vec2) +
           p.joints.size() * sizeof(glm::uvec4) + p.weights.size() * sizeof(glm::vec4) +
           p.indices.size() * sizeof(uint32_t);
}

// A mesh as the file has it, before it is placed by the nodes that use it.
struct FileMesh {
    Mesh mesh;
    std::vector<std::string> wheres; // "meshes[m].primitives[p]" of each primitive kept
};

Result<FileMesh> readMesh(const tinygltf::Model& model, size_t index, ImportBudget& budget) {
    const tinygltf::Mesh& source = model.meshes[index];
    FileMesh result;
    result.mesh.name = source.name.empty() ? "mesh_" + std::to_string(index) : source.name;
    for (size_t p = 0; p < source.primitives.size(); ++p) {
        const std::string where = at(at("meshes", index) + ".primitives", p);
        const int mode = source.primitives[p].mode;
        if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_TRIANGLE_FAN)
            return Error{where + ".mode: " + std::to_string(mode) + " is not a primitive mode"};
        if (mode != TINYGLTF_MODE_TRIANGLES) continue; // points, lines, strips, fans: skipped
        Result<Primitive> primitive = readPrimitive(model, source.primitives[p], where, budget);
        if (!primitive) return primitive.error();
        // Charged as it is read: a mesh of many primitives reading one accessor of zeros is
        // stopped before it is whole.
        if (Status s = budget.spend(where, 0, primitive.value().positions.size(),
                                    primitiveBytes(primitive.value()));
            !s)
            return s.error();
        result.mesh.primitives.push_back(std::move(primitive).value());
        result.wheres.push_back(where);
    }
    return result;
}

// Gives a copy of a file mesh its place: skinned by `skin`, or attached to `node`, or neither.
Status placeMesh(const FileMesh& fileMesh, int skin, int node, const Character& character,
                 Mesh& mesh) {
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        Primitive& primitive = mesh.primitives[p];
        const std::string& where = fileMesh.wheres[p];
        primitive.skin = skin;
        primitive.node = skin >= 0 ? -1 : node;
        if (skin < 0) {
            primitive.joints.clear();
            primitive.weights.clear();
            continue;
        }
        if (primitive.joints.empty())
            return Error{where + ".attributes: no JOINTS_0/WEIGHTS_0 on a mesh skinned by " +
                         at("skins", size_t(skin))};
        const size_t jointCount = character.skins[size_t(skin)].joints.size();
        for (const glm::uvec4& joints : primitive.joints)
            for (int k = 0; k < 4; ++k)
                if (joints[k] >= jointCount)
                    return Error{where + ".attributes.JOINTS_0: joint " +
                                 std::to_string(joints[k]) + " >= " + std::to_string(jointCount) +
                                 " joints of " + at("skins", size_t(skin))};
    }
    return Ok{};
}

struct MeshSize {
    uint64_t vertices = 0;
    uint64_t bytes = 0; // its arrays and the structs that hold them
};

MeshSize meshSize(const Mesh& mesh) {
    MeshSize size;
    size.bytes = sizeof(Mesh) + mesh.name.size();
    for (const Primitive& p : mesh.primitives) {
        size.vertices += p.positions.size();
        size.bytes += primitiveBytes(p);
    }
    return size;
}

Status readMeshes(const tinygltf::Model& model, const NodeOrder& order, Character& character,
                  ImportBudget& budget) {
    // The nodes instancing each mesh, in the character's node order.
    std::vector<std::vector<int>> users(model.meshes.size());
    for (int fileIndex : order.order) {
        const int mesh = model.nodes[size_t(fileIndex)].mesh;
        if (mesh >= 0) users[size_t(mesh)].push_back(fileIndex);
    }
    for (size_t m = 0; m < model.meshes.size(); ++m) {
        Result<FileMesh> fileMesh = readMesh(model, m, budget);
        if (!fileMesh) return fileMesh.error();
        // The copies placed below: their bytes each (the file's mesh is held beside them), their
        // vertices past the first (readMesh charged the file's).
        const uint64_t copies = std::max<size_t>(users[m].size(), 1);
        const MeshSize size = meshSize(fileMesh.value().mesh);
        if (Status s =
                budget.spend(at("meshes", m), 0, (copies - 1) * size.vertices, copies * size.bytes);
            !s)
            return s;
        if (users[m].empty()) {
            Mesh mesh = fileMesh.value().mesh;
            if (Status s = placeMesh(fileMesh.value(), -1, -1, character, mesh); !s) return s;
            character.meshes.push_back(std::move(mesh));
            continue;
        }
        for (size_t k = 0; k < users[m].size(); ++k) {
            const int fileNode = users[m][k];
            const int node = order.newIndex[size_t(fileNode)];
            Mesh mesh = fileMesh.value().mesh;
            if (k > 0) mesh.name += "@" + character.nodes[size_t(node)].name;
            const int skin = model.nodes[size_t(fileNode)].skin;
            if (Status s = placeMesh(fileMesh.value(), skin, node, character, mesh); !s) return s;
            character.meshes.push_back(std::move(mesh));
        }
    }
    return Ok{};
}

// --- Animations --------------------------------------------------------------------------------

struct Sampler {
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times;
    int output = -1;
};

Result<Interpolation> interpolation(const std::string& name, const std::string& where) {
    if (name == "LINEAR") return Interpolation::Linear;
    if (name == "STEP") return Interpolation::Step;
    if (name == "CUBICSPLINE") return Interpolation::CubicSpline;
    return Error{where + ".interpolation: '" + firstLine(name) +
                 "' is not LINEAR, STEP or CUBICSPLINE"};
}

Result<Sampler> readSampler(const tinygltf::Model& model, const tinygltf::AnimationSampler& source,
                            const std::string& where, ImportBudget& budget) {
    Sampler sampler;
    Result<Interpolation> kind = interpolation(source.interpolation, where);
    if (!kind) return kind.error();
    sampler.interpolation = kind.value();
    const std::string inputWhere = where + ".input";
    Result<std::vector<glm::vec4>> times =
        readFloats(model, source.input, inputWhere, floatFormat(TINYGLTF_TYPE_SCALAR), budget);
    if (!times) return times.error();
    for (size_t k = 0; k < times.value().size(); ++k) {
        const float t = times.value()[k].x;
        if (t < 0.0f)
            return Error{inputWhere + ": key " + std::to_string(k) + " at " + number(t) +
                         " s is negative"};
        if (k > 0 && !(t > sampler.times.back()))
            return Error{inputWhere + ": key times do not increase at key " + std::to_string(k) +
                         " (" + number(t) + " after " + number(sampler.times.back()) + ")"};
        sampler.times.push_back(t);
    }
    if (source.output < 0 || size_t(source.output) >= model.accessors.size())
        return Error{where + ".output: accessor " + std::to_string(source.output) +
                     " does not exist"};
    sampler.output = source.output;
    return sampler;
}

std::optional<Path> channelPath(const std::string& name) {
    if (name == "translation") return Path::Translation;
    if (name == "rotation") return Path::Rotation;
    if (name == "scale") return Path::Scale;
    return std::nullopt; // "weights" (morph targets) or an extension's path: not animated here
}

// Unit quaternions for the key values; CUBICSPLINE tangents are left as they are.
Status normaliseRotations(Channel& channel, const std::string& where) {
    const bool cubic = channel.interpolation == Interpolation::CubicSpline;
    const size_t perKey = cubic ? 3 : 1;
    for (size_t i = cubic ? 1 : 0; i < channel.values.size(); i += perKey) {
        const float length = glm::length(channel.values[i]);
        if (!(length > 0.0f) || !std::isfinite(length))
            return Error{where + ": key " + std::to_string(i / perKey) +
                         " is not a rotation (zero quaternion)"};
        channel.values[i] /= length;
    }
    return Ok{};
}

Result<Channel> readChannel(const tinygltf::Model& model, const Sampler& sampler, Path path,
                            const std::string& samplerWhere, ImportBudget& budget) {
    Channel channel;
    channel.path = path;
    channel.interpolation = sampler.interpolation;
    if (Status s =
            budget.spend(samplerWhere + ".input", 0, 0, sampler.times.size() * sizeof(float));
        !s)
        return s.error();
    channel.times = sampler.times;
    Format format = floatFormat(path == Path::Rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3);
    if (path == Path::Rotation) format.signedNormalized = format.unsignedNormalized = true;
    const std::string outputWhere = samplerWhere + ".output";
    Result<std::vector<glm::vec4>> values =
        readFloats(model, sampler.output, outputWhere, format, budget);
    if (!values) return values.error();
    const size_t perKey = sampler.interpolation == Interpolation::CubicSpline ? 3 : 1;
    if (values.value().size() != perKey * sampler.times.size())
        return Error{outputWhere + ": " + std::to_string(values.value().size()) + " values for " +
                     std::to_string(sampler.times.size()) + " keys" +
                     (perKey == 3 ? " (CUBICSPLINE needs 3 per key)" : "")};
    channel.values = std::move(values).value();
    if (path == Path::Rotation)
        if (Status s = normaliseRotations(channel, outputWhere); !s) return s.error();
    return channel;
}

Result<Clip> readClip(const tinygltf::Model& model, size_t index, const NodeOrder& order,
                      ImportBudget& budget) {
    const tinygltf::Animation& source = model.animations[index];
    const std::string where = at("animations", index);
    Clip clip;
    clip.name = source.name.empty() ? "clip_" + std::to_string(index) : source.name;
    std::vector<Sampler> samplers;
    for (size_t s = 0; s < source.samplers.size(); ++s) {
        Result<Sampler> sampler =
            readSampler(model, source.samplers[s], at(where + ".samplers", s), budget);
        if (!sampler) return sampler.error();
        samplers.push_back(std::move(sampler).value());
    }
    for (size_t c = 0; c < source.channels.size(); ++c) {
        const tinygltf::AnimationChannel& channel = source.channels[c];
        const std::string channelWhere = at(where + ".channels", c);
        if (channel.sampler < 0 || size_t(channel.sampler) >= samplers.size())
            return Error{channelWhere + ".sampler: sampler " + std::to_string(channel.sampler) +
                         " does not exist"};
        if (channel.target_node >= 0 && size_t(channel.target_node) >= model.nodes.size())
            return Error{channelWhere + ".target.node: node " +
                         std::to_string(channel.target_node) + " does not exist"};
        const std::optional<Path> path = channelPath(channel.target_path);
        if (channel.target_node < 0 || !path) continue;
        const size_t s = size_t(channel.sampler);
        Result<Channel> read =
            readChannel(model, samplers[s], *path, at(where + ".samplers", s), budget);
        if (!read) return read.error();
        read.value().node = order.newIndex[size_t(channel.target_node)];
        clip.duration = std::max(clip.duration, read.value().times.back());
        clip.channels.push_back(std::move(read).value());
    }
    return clip;
}

Status readClips(const tinygltf::Model& model, const NodeOrder& order, Character& character,
                 ImportBudget& budget) {
    for (size_t a = 0; a < model.animations.size(); ++a) {
        Result<Clip> clip = readClip(model, a, order, budget);
        if (!clip) return clip.error();
        character.clips.push_back(std::move(clip).value());
    }
    return Ok{};
}

// --- The whole file ----------------------------------------------------------------------------

Result<Character> importChecked(const std::filesystem::path& file) {
    Result<Bytes> bytes = readBytes(file);
    if (!bytes) return bytes.error();
    Result<tinygltf::Model> model = parseModel(bytes.value(), file);
    if (!model) return model.error();
    const tinygltf::Model& gltf = model.value();

    Result<NodeOrder> order = orderNodes(gltf);
    if (!order) return order.error();
    Character character;
    character.name = file.stem().string();
    ImportBudget budget;
    for (auto read : {&readNodes, &readSkins, &readMeshes, &readClips})
        if (Status s = read(gltf, order.value(), character, budget); !s) return s.error();
    if (Status s = checkInvariants(character); !s) return s.error();
    return character;
}

} // namespace

Result<Character> importGltf(const std::filesystem::path& file) {
    Result<Character> character = Error{};
    try {
        character = importChecked(file);
    } catch (const std::exception& e) {
        // tinygltf (or an allocation) may throw on malformed input; it ends up as any refusal.
        character = Error{"cannot parse the file (" + firstLine(e.what()) + ")"};
    } catch (...) {
        character = Error{"cannot parse the file"};
    }
    if (!character) return Error{file.string() + ": " + character.error().message};
    return character;
}

} // namespace mfx::anim
