#include "core/anim/gltf_export.h"

#include "core/enum_names.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <system_error>
#include <tuple>
#include <vector>

namespace mfx::anim {

namespace {

using json = nlohmann::json;

// glTF 2.0 constants (the specification's accessor.componentType and bufferView.target values).
constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kFloat = 5126;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

constexpr uint32_t kGlbMagic = 0x46546C67;     // "glTF"
constexpr uint32_t kGlbJsonChunk = 0x4E4F534A; // "JSON"
constexpr uint32_t kGlbBinChunk = 0x004E4942;  // "BIN\0"

// The document being built: its JSON and its one binary buffer.
class Writer {
public:
    json doc = json::object();
    std::vector<unsigned char> bin;

    // Appends `bytes` as a new buffer view (4-byte aligned) and an accessor over it; returns the
    // accessor's index. `count` elements of `type` ("SCALAR", "VEC3", ...).
    int addAccessor(const void* bytes, size_t byteLength, int componentType, size_t count,
                    const char* type, int target = 0, bool normalized = false) {
        while (bin.size() % 4 != 0)
            bin.push_back(0);
        json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", byteLength}};
        if (target != 0) view["target"] = target;
        const auto* begin = static_cast<const unsigned char*>(bytes);
        bin.insert(bin.end(), begin, begin + byteLength);
        json& views = doc["bufferViews"];
        views.push_back(std::move(view));
        json accessor = {{"bufferView", views.size() - 1},
                         {"componentType", componentType},
                         {"count", count},
                         {"type", type}};
        if (normalized) accessor["normalized"] = true;
        json& accessors = doc["accessors"];
        accessors.push_back(std::move(accessor));
        return int(accessors.size() - 1);
    }

    json& accessor(int index) { return doc["accessors"][size_t(index)]; }

    // Float vectors of N components (N = 1..4 taken from each glm vector).
    template <int N, typename Vec>
    int addFloats(const std::vector<Vec>& values, const char* type, int target = 0,
                  bool withBounds = false) {
        std::vector<float> flat;
        flat.reserve(values.size() * N);
        for (const Vec& v : values)
            for (int c = 0; c < N; ++c)
                flat.push_back(v[c]);
        const int index = addAccessor(flat.data(), flat.size() * sizeof(float), kFloat,
                                      values.size(), type, target);
        if (withBounds && !values.empty()) {
            json low = json::array();
            json high = json::array();
            for (int c = 0; c < N; ++c) {
                float lo = std::numeric_limits<float>::max();
                float hi = std::numeric_limits<float>::lowest();
                for (size_t i = 0; i < values.size(); ++i) {
                    lo = std::min(lo, flat[i * N + size_t(c)]);
                    hi = std::max(hi, flat[i * N + size_t(c)]);
                }
                low.push_back(lo);
                high.push_back(hi);
            }
            accessor(index)["min"] = std::move(low);
            accessor(index)["max"] = std::move(high);
        }
        return index;
    }

    int addTimes(const std::vector<float>& times) {
        const int index =
            addAccessor(times.data(), times.size() * sizeof(float), kFloat, times.size(), "SCALAR");
        accessor(index)["min"] = json::array({times.front()});
        accessor(index)["max"] = json::array({times.back()});
        return index;
    }

    template <typename T>
    int addIntegers(const std::vector<T>& values, int componentType, size_t count, const char* type,
                    int target) {
        return addAccessor(values.data(), values.size() * sizeof(T), componentType, count, type,
                           target);
    }
};

json floatArray(const float* values, int n) {
    json out = json::array();
    for (int i = 0; i < n; ++i)
        out.push_back(values[i]);
    return out;
}

json nodeJson(const Node& node) {
    const Transform& t = node.rest;
    const float rotation[4] = {t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w};
    return {{"name", node.name},
            {"translation", floatArray(&t.translation.x, 3)},
            {"rotation", floatArray(rotation, 4)},
            {"scale", floatArray(&t.scale.x, 3)}};
}

// How a mesh is placed: by a skin, by a node, or not at all. Every primitive must agree.
Result<std::pair<int, int>> placement(const Mesh& mesh, size_t index) {
    if (mesh.primitives.empty()) return std::pair<int, int>{-1, -1};
    for (size_t p = 0; p < mesh.primitives.size(); ++p)
        if (mesh.primitives[p].positions.empty())
            return Error{"meshes[" + std::to_string(index) + "] (\"" + mesh.name +
                         "\").primitives[" + std::to_string(p) +
                         "]: no vertices; a glTF accessor holds at least one"};
    const Primitive& first = mesh.primitives.front();
    for (size_t p = 1; p < mesh.primitives.size(); ++p)
        if (mesh.primitives[p].skin != first.skin || mesh.primitives[p].node != first.node)
            return Error{"meshes[" + std::to_string(index) + "] (\"" + mesh.name +
                         "\"): primitives " + std::to_string(p) +
                         " and 0 are placed differently (skin or node); glTF places a whole mesh"};
    return std::pair<int, int>{first.skin, first.node};
}

json primitiveJson(Writer& w, const Character& character, const Primitive& p,
                   std::map<std::tuple<float, float, float, float>, int>& materials) {
    json attributes = {
        {"POSITION", w.addFloats<3>(p.positions, "VEC3", kArrayBuffer, /*withBounds=*/true)}};
    if (!p.normals.empty()) attributes["NORMAL"] = w.addFloats<3>(p.normals, "VEC3", kArrayBuffer);
    if (!p.uvs.empty()) attributes["TEXCOORD_0"] = w.addFloats<2>(p.uvs, "VEC2", kArrayBuffer);
    if (!p.joints.empty() && p.skin >= 0) {
        const size_t jointCount = character.skins[size_t(p.skin)].joints.size();
        if (jointCount <= 256) {
            std::vector<uint8_t> joints;
            for (const glm::uvec4& j : p.joints)
                for (int c = 0; c < 4; ++c)
                    joints.push_back(uint8_t(j[c]));
            attributes["JOINTS_0"] =
                w.addIntegers(joints, kUnsignedByte, p.joints.size(), "VEC4", kArrayBuffer);
        } else {
            std::vector<uint16_t> joints;
            for (const glm::uvec4& j : p.joints)
                for (int c = 0; c < 4; ++c)
                    joints.push_back(uint16_t(j[c]));
            attributes["JOINTS_0"] =
                w.addIntegers(joints, kUnsignedShort, p.joints.size(), "VEC4", kArrayBuffer);
        }
        attributes["WEIGHTS_0"] = w.addFloats<4>(p.weights, "VEC4", kArrayBuffer);
    }
    json out = {{"attributes", std::move(attributes)}, {"mode", 4}};
    if (!p.indices.empty()) {
        if (p.positions.size() <= 65536) {
            const std::vector<uint16_t> narrow(p.indices.begin(), p.indices.end());
            out["indices"] =
                w.addIntegers(narrow, kUnsignedShort, narrow.size(), "SCALAR", kElementArrayBuffer);
        } else {
            out["indices"] = w.addIntegers(p.indices, kUnsignedInt, p.indices.size(), "SCALAR",
                                           kElementArrayBuffer);
        }
    }
    const auto key = std::make_tuple(p.baseColor.r, p.baseColor.g, p.baseColor.b, p.baseColor.a);
    auto found = materials.find(key);
    if (found == materials.end()) {
        json& list = w.doc["materials"];
        list.push_back({{"name", "material_" + std::to_string(list.size())},
                        {"pbrMetallicRoughness",
                         {{"baseColorFactor", floatArray(&p.baseColor.r, 4)},
                          {"metallicFactor", 0.0},
                          {"roughnessFactor", 0.8}}}});
        found = materials.emplace(key, int(list.size() - 1)).first;
    }
    out["material"] = found->second;
    return out;
}

const char* pathName(Path path) {
    static constexpr NamedValue<Path> kNames[] = {
        {Path::Translation, "translation"}, {Path::Rotation, "rotation"}, {Path::Scale, "scale"}};
    return nameOf(path, kNames, "translation");
}

const char* interpolationName(Interpolation interpolation) {
    static constexpr NamedValue<Interpolation> kNames[] = {
        {Interpolation::Linear, "LINEAR"},
        {Interpolation::Step, "STEP"},
        {Interpolation::CubicSpline, "CUBICSPLINE"}};
    return nameOf(interpolation, kNames, "LINEAR");
}

json animationJson(Writer& w, const Clip& clip) {
    json samplers = json::array();
    json channels = json::array();
    for (const Channel& channel : clip.channels) {
        const int input = w.addTimes(channel.times);
        const int output = channel.path == Path::Rotation ? w.addFloats<4>(channel.values, "VEC4")
                                                          : w.addFloats<3>(channel.values, "VEC3");
        samplers.push_back({{"input", input},
                            {"output", output},
                            {"interpolation", interpolationName(channel.interpolation)}});
        channels.push_back(
            {{"sampler", samplers.size() - 1},
             {"target", {{"node", channel.node}, {"path", pathName(channel.path)}}}});
    }
    return {
        {"name", clip.name}, {"samplers", std::move(samplers)}, {"channels", std::move(channels)}};
}

Result<Writer> buildDocument(const Character& character) {
    Writer w;
    w.doc["asset"] = {{"version", "2.0"}, {"generator", "motionfx"}};
    w.doc["accessors"] = json::array();
    w.doc["bufferViews"] = json::array();

    json nodes = json::array();
    for (const Node& node : character.nodes)
        nodes.push_back(nodeJson(node));
    json roots = json::array();
    for (size_t i = 0; i < character.nodes.size(); ++i) {
        const int parent = character.nodes[i].parent;
        if (parent < 0)
            roots.push_back(i);
        else
            nodes[size_t(parent)]["children"].push_back(i);
    }

    json meshes = json::array();
    std::map<std::tuple<float, float, float, float>, int> materials;
    for (size_t m = 0; m < character.meshes.size(); ++m) {
        const Mesh& mesh = character.meshes[m];
        const Result<std::pair<int, int>> placed = placement(mesh, m);
        if (!placed) return placed.error();
        json primitives = json::array();
        for (const Primitive& p : mesh.primitives)
            primitives.push_back(primitiveJson(w, character, p, materials));
        meshes.push_back({{"name", mesh.name}, {"primitives", std::move(primitives)}});
        const auto [skin, node] = placed.value();
        if (skin >= 0) {
            roots.push_back(nodes.size());
            nodes.push_back({{"name", mesh.name}, {"mesh", m}, {"skin", skin}});
        } else if (node >= 0) {
            if (nodes[size_t(node)].contains("mesh"))
                return Error{"meshes[" + std::to_string(m) + "] (\"" + mesh.name + "\"): node \"" +
                             character.nodes[size_t(node)].name +
                             "\" already carries a mesh; glTF gives a node one"};
            nodes[size_t(node)]["mesh"] = m;
        }
    }

    json skins = json::array();
    for (const Skin& skin : character.skins) {
        json entry = {{"name", skin.name}, {"joints", skin.joints}};
        if (!skin.joints.empty())
            entry["inverseBindMatrices"] =
                w.addAccessor(skin.inverseBind.data(), skin.inverseBind.size() * sizeof(glm::mat4),
                              kFloat, skin.inverseBind.size(), "MAT4");
        skins.push_back(std::move(entry));
    }

    json animations = json::array();
    for (const Clip& clip : character.clips)
        if (!clip.channels.empty()) animations.push_back(animationJson(w, clip));

    w.doc["scene"] = 0;
    w.doc["scenes"] = json::array({{{"name", character.name}, {"nodes", std::move(roots)}}});
    w.doc["nodes"] = std::move(nodes);
    if (!meshes.empty()) w.doc["meshes"] = std::move(meshes);
    if (!skins.empty()) w.doc["skins"] = std::move(skins);
    if (!animations.empty()) w.doc["animations"] = std::move(animations);
    if (w.doc["accessors"].empty()) w.doc.erase("accessors");
    if (w.doc["bufferViews"].empty()) w.doc.erase("bufferViews");
    return w;
}

std::string base64(const std::vector<unsigned char>& bytes) {
    static const char* alphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t a = bytes[i];
        const uint32_t b = i + 1 < bytes.size() ? bytes[i + 1] : 0;
        const uint32_t c = i + 2 < bytes.size() ? bytes[i + 2] : 0;
        const uint32_t triple = (a << 16) | (b << 8) | c;
        out.push_back(alphabet[(triple >> 18) & 63]);
        out.push_back(alphabet[(triple >> 12) & 63]);
        out.push_back(i + 1 < bytes.size() ? alphabet[(triple >> 6) & 63] : '=');
        out.push_back(i + 2 < bytes.size() ? alphabet[triple & 63] : '=');
    }
    return out;
}

void appendU32(std::string& out, uint32_t value) {
    char bytes[4];
    std::memcpy(bytes, &value, 4); // GLB is little-endian, as is every target of this project
    out.append(bytes, 4);
}

// The GLB container: 12-byte header, a JSON chunk padded with spaces, a BIN chunk padded with
// zeros (glTF 2.0 specification, "GLB File Format Specification").
Result<std::string> glbBytes(const std::string& text, const std::vector<unsigned char>& bin) {
    std::string jsonChunk = text;
    while (jsonChunk.size() % 4 != 0)
        jsonChunk.push_back(' ');
    std::string binChunk(bin.begin(), bin.end());
    while (binChunk.size() % 4 != 0)
        binChunk.push_back('\0');
    const uint64_t total = 12 + 8 + uint64_t(jsonChunk.size()) +
                           (binChunk.empty() ? 0 : 8 + uint64_t(binChunk.size()));
    if (total > std::numeric_limits<uint32_t>::max())
        return Error{"the character needs " + std::to_string(total) +
                     " bytes; a .glb holds at most 4 GiB"};
    std::string out;
    out.reserve(size_t(total));
    appendU32(out, kGlbMagic);
    appendU32(out, 2);
    appendU32(out, uint32_t(total));
    appendU32(out, uint32_t(jsonChunk.size()));
    appendU32(out, kGlbJsonChunk);
    out += jsonChunk;
    if (!binChunk.empty()) {
        appendU32(out, uint32_t(binChunk.size()));
        appendU32(out, kGlbBinChunk);
        out += binChunk;
    }
    return out;
}

} // namespace

Status exportGltf(const Character& character, const std::filesystem::path& file) {
    const std::string where = file.string();
    if (Status valid = checkInvariants(character); !valid)
        return Error{where + ": cannot export: " + valid.error().message};
    Result<Writer> built = buildDocument(character);
    if (!built) return Error{where + ": cannot export: " + built.error().message};
    Writer& w = built.value();

    const bool binary = file.extension() == ".glb";
    if (!w.bin.empty()) {
        json buffer = {{"byteLength", w.bin.size()}};
        if (!binary) buffer["uri"] = "data:application/octet-stream;base64," + base64(w.bin);
        w.doc["buffers"] = json::array({std::move(buffer)});
    }
    std::string bytes;
    if (binary) {
        Result<std::string> glb = glbBytes(w.doc.dump(), w.bin);
        if (!glb) return Error{where + ": " + glb.error().message};
        bytes = std::move(glb).value();
    } else {
        bytes = w.doc.dump(1, '\t') + "\n";
    }

    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
        return Error{where + ": is a directory; give a file name ending in .glb or .gltf"};
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    if (!out) return Error{"cannot write " + where};
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (!out) return Error{"cannot write " + where + " (write failed)"};
    return Ok{};
}

} // namespace mfx::anim
