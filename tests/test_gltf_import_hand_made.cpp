// The glTF importer on small hand-made files: each breaks one rule and is refused with one line
// naming the file and the fault, or uses one feature (node matrices, external buffers, GLB).
#include "core/anim/gltf_import.h"

#include "tests/gltf_load.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace {

using mfx::anim::Character;
using mfx::anim::importGltf;
using mfx::test::load;
using nlohmann::json;

std::string base64(const std::vector<unsigned char>& bytes) {
    static const char* alphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t chunk = uint32_t(bytes[i]) << 16 |
                               (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                               (i + 2 < bytes.size() ? uint32_t(bytes[i + 2]) : 0);
        for (int k = 0; k < 4; ++k)
            out += i * 8 + size_t(k) * 6 < bytes.size() * 8 ? alphabet[(chunk >> (18 - 6 * k)) & 63]
                                                            : '=';
    }
    return out;
}

// A glTF document under construction, with one binary buffer that views and accessors point into.
struct Document {
    json gltf = {{"asset", {{"version", "2.0"}}}};
    std::vector<unsigned char> bin;

    template <typename T>
    int addAccessor(const std::vector<T>& values, int componentType, const char* type,
                    size_t count) {
        while (bin.size() % 4 != 0)
            bin.push_back(0);
        const size_t offset = bin.size();
        const size_t bytes = values.size() * sizeof(T);
        bin.resize(offset + bytes);
        std::memcpy(bin.data() + offset, values.data(), bytes);
        gltf["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
        gltf["accessors"].push_back({{"bufferView", gltf["bufferViews"].size() - 1},
                                     {"componentType", componentType},
                                     {"type", type},
                                     {"count", count}});
        return int(gltf["accessors"].size() - 1);
    }

    json withEmbeddedBuffer() const {
        json out = gltf;
        out["buffers"] =
            json::array({{{"byteLength", bin.size()},
                          {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
        return out;
    }
};

// What the rigged triangle is made of; each test changes one thing.
struct TriangleSpec {
    std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::vector<uint8_t> joints = {0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0};
    std::vector<float> weights = {0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    std::vector<float> times = {0.0f, 0.5f, 1.0f};
    size_t inverseBindMatrices = 2;
};

constexpr int kFloat = 5126;
constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;

// A triangle skinned to two joints (node 0 root, node 1 its child; node 2 holds the mesh and the
// skin) with one clip rotating node 1. Accessors: 0 POSITION, 1 JOINTS_0, 2 WEIGHTS_0,
// 3 indices, 4 inverse bind matrices, 5 key times, 6 rotations.
Document riggedTriangle(const TriangleSpec& spec = {}) {
    Document d;
    d.addAccessor(spec.positions, kFloat, "VEC3", spec.positions.size() / 3);
    d.addAccessor(spec.joints, kUnsignedByte, "VEC4", spec.joints.size() / 4);
    d.addAccessor(spec.weights, kFloat, "VEC4", spec.weights.size() / 4);
    d.addAccessor(std::vector<uint16_t>{0, 1, 2, 0}, kUnsignedShort, "SCALAR", 3);
    std::vector<float> matrices;
    for (size_t m = 0; m < spec.inverseBindMatrices; ++m)
        for (int i = 0; i < 16; ++i)
            matrices.push_back(i % 5 == 0 ? 1.0f : 0.0f);
    d.addAccessor(matrices, kFloat, "MAT4", spec.inverseBindMatrices);
    d.addAccessor(spec.times, kFloat, "SCALAR", spec.times.size());
    std::vector<float> rotations;
    for (size_t k = 0; k < spec.times.size(); ++k)
        rotations.insert(rotations.end(), {0.0f, 0.0f, float(k), 1.0f}); // normalised on import
    d.addAccessor(rotations, kFloat, "VEC4", spec.times.size());
    d.gltf["nodes"] = json::array({{{"name", "root"}, {"children", {1}}},
                                   {{"name", "tip"}, {"translation", {0, 1, 0}}},
                                   {{"name", "body"}, {"mesh", 0}, {"skin", 0}}});
    d.gltf["meshes"] =
        json::array({{{"name", "triangle"},
                      {"primitives",
                       {{{"attributes", {{"POSITION", 0}, {"JOINTS_0", 1}, {"WEIGHTS_0", 2}}},
                         {"indices", 3}}}}}});
    d.gltf["skins"] = json::array({{{"joints", {0, 1}}, {"inverseBindMatrices", 4}}});
    d.gltf["animations"] = json::array(
        {{{"name", "bend"},
          {"samplers", {{{"input", 5}, {"output", 6}, {"interpolation", "LINEAR"}}}},
          {"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "rotation"}}}}}}}});
    return d;
}

std::string outputPath(const std::string& name) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/gltf_import";
    std::filesystem::create_directories(dir);
    return dir + "/" + name;
}

std::string writeGltf(const std::string& name, const json& gltf) {
    const std::string path = outputPath(name);
    std::ofstream(path) << gltf.dump(1);
    return path;
}

// The error importing `gltf` (written as `name`) gives; fails the test if it loads.
std::string refusal(const std::string& name, const json& gltf) {
    const mfx::Result<Character> result = importGltf(writeGltf(name, gltf));
    EXPECT_FALSE(result.ok()) << name << " loaded";
    if (result) return {};
    const std::string& message = result.error().message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find(name), std::string::npos) << message;
    return message;
}

#define EXPECT_CONTAINS(text, part)                                                                \
    EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

TEST(GltfImportHandMade, TheRiggedTriangleLoads) {
    const Character c = load(writeGltf("triangle.gltf", riggedTriangle().withEmbeddedBuffer()));
    ASSERT_EQ(c.nodes.size(), 3u);
    EXPECT_EQ(c.nodes[1].parent, 0);
    ASSERT_EQ(c.meshes.size(), 1u);
    EXPECT_EQ(c.meshes[0].name, "triangle");
    EXPECT_EQ(c.meshes[0].primitives[0].skin, 0);
    EXPECT_EQ(c.meshes[0].primitives[0].node, -1);
    // No NORMAL in the file: computed, the triangle lies in z = 0.
    for (const glm::vec3& n : c.meshes[0].primitives[0].normals)
        EXPECT_NEAR(n.z, 1.0f, 1e-6f);
    ASSERT_EQ(c.clips.size(), 1u);
    EXPECT_EQ(c.clips[0].name, "bend");
    EXPECT_FLOAT_EQ(c.clips[0].duration, 1.0f);
    EXPECT_NEAR(glm::length(c.clips[0].channels[0].values[2]), 1.0f, 1e-6f);
}

TEST(GltfImportHandMade, UnresolvedJointIsRefused) {
    Document d = riggedTriangle();
    d.gltf["skins"][0]["joints"] = {0, 7};
    EXPECT_CONTAINS(refusal("unresolved_joint.gltf", d.withEmbeddedBuffer()),
                    "skins[0].joints[1]: node 7 does not exist");
}

TEST(GltfImportHandMade, InverseBindMatrixCountMismatchIsRefused) {
    TriangleSpec spec;
    spec.inverseBindMatrices = 3;
    EXPECT_CONTAINS(refusal("ibm_count.gltf", riggedTriangle(spec).withEmbeddedBuffer()),
                    "skins[0].inverseBindMatrices: 3 matrices for 2 joints");
}

TEST(GltfImportHandMade, ChannelSamplerOutOfRangeIsRefused) {
    Document d = riggedTriangle();
    d.gltf["animations"][0]["channels"][0]["sampler"] = 4;
    EXPECT_CONTAINS(refusal("channel_sampler.gltf", d.withEmbeddedBuffer()),
                    "animations[0].channels[0].sampler: sampler 4 does not exist");
}

TEST(GltfImportHandMade, ChannelTargetOutOfRangeIsRefused) {
    Document d = riggedTriangle();
    d.gltf["animations"][0]["channels"][0]["target"]["node"] = 30;
    EXPECT_CONTAINS(refusal("channel_node.gltf", d.withEmbeddedBuffer()),
                    "animations[0].channels[0].target.node: node 30 does not exist");
}

TEST(GltfImportHandMade, SamplerAccessorOutOfRangeIsRefused) {
    Document d = riggedTriangle();
    d.gltf["animations"][0]["samplers"][0]["output"] = 99;
    EXPECT_CONTAINS(refusal("sampler_output.gltf", d.withEmbeddedBuffer()),
                    "animations[0].samplers[0].output: accessor 99 does not exist");
}

TEST(GltfImportHandMade, KeyTimesNotIncreasingAreRefused) {
    TriangleSpec spec;
    spec.times = {0.0f, 0.5f, 0.5f};
    EXPECT_CONTAINS(refusal("times.gltf", riggedTriangle(spec).withEmbeddedBuffer()),
                    "animations[0].samplers[0].input: key times do not increase at key 2");
}

TEST(GltfImportHandMade, NonFiniteKeyTimeIsRefused) {
    TriangleSpec spec;
    spec.times = {0.0f, 0.5f, std::numeric_limits<float>::infinity()};
    EXPECT_CONTAINS(refusal("times_inf.gltf", riggedTriangle(spec).withEmbeddedBuffer()),
                    "animations[0].samplers[0].input: element 2 is not finite");
}

TEST(GltfImportHandMade, JointIndexBeyondTheSkinIsRefused) {
    TriangleSpec spec;
    spec.joints[5] = 5;
    EXPECT_CONTAINS(refusal("joint_range.gltf", riggedTriangle(spec).withEmbeddedBuffer()),
                    "meshes[0].primitives[0].attributes.JOINTS_0: joint 5 >= 2 joints of skins[0]");
}

TEST(GltfImportHandMade, AccessorPastItsBufferViewIsRefused) {
    Document d = riggedTriangle();
    d.gltf["accessors"][0]["byteOffset"] = 8;
    EXPECT_CONTAINS(refusal("accessor_range.gltf", d.withEmbeddedBuffer()),
                    "meshes[0].primitives[0].attributes.POSITION: accessors[0]: 3 elements from "
                    "byte 8 run past the end of bufferViews[0] (36 bytes)");
}

TEST(GltfImportHandMade, BufferViewPastItsBufferIsRefused) {
    Document d = riggedTriangle();
    d.gltf["bufferViews"][0]["byteLength"] = 1u << 30;
    EXPECT_CONTAINS(refusal("view_range.gltf", d.withEmbeddedBuffer()),
                    "bufferViews[0]: 1073741824 bytes from byte 0 run past the end of buffers[0]");
}

TEST(GltfImportHandMade, HugeCountDoesNotOverflow) {
    Document d = riggedTriangle();
    d.gltf["accessors"][0]["count"] = 0x5555555555555556ull; // count * 12 wraps around 2^64
    EXPECT_CONTAINS(refusal("huge_count.gltf", d.withEmbeddedBuffer()), "accessors[0]");
}

TEST(GltfImportHandMade, WrongComponentTypeIsRefused) {
    Document d = riggedTriangle();
    d.gltf["accessors"][1]["componentType"] = kFloat;
    EXPECT_CONTAINS(refusal("joints_float.gltf", d.withEmbeddedBuffer()),
                    "attributes.JOINTS_0: accessors[1] holds VEC4 of float");
}

TEST(GltfImportHandMade, NotFinitePositionIsRefused) {
    TriangleSpec spec;
    spec.positions[4] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_CONTAINS(refusal("nan.gltf", riggedTriangle(spec).withEmbeddedBuffer()),
                    "attributes.POSITION: element 1 is not finite");
}

TEST(GltfImportHandMade, NodeWithTwoParentsIsRefused) {
    Document d = riggedTriangle();
    d.gltf["nodes"][2]["children"] = {1};
    EXPECT_CONTAINS(refusal("two_parents.gltf", d.withEmbeddedBuffer()),
                    "nodes[1]: child of both nodes[0] and nodes[2]");
}

TEST(GltfImportHandMade, NodeCycleIsRefused) {
    Document d = riggedTriangle();
    d.gltf["nodes"][1]["children"] = {2};
    d.gltf["nodes"][2]["children"] = {1};
    d.gltf["nodes"][0].erase("children");
    EXPECT_CONTAINS(refusal("cycle.gltf", d.withEmbeddedBuffer()), "has a cycle");
}

TEST(GltfImportHandMade, ChildrenBeforeParentsAreReordered) {
    Document d = riggedTriangle();
    // The file lists the tip first, its parent second.
    std::swap(d.gltf["nodes"][0], d.gltf["nodes"][1]);
    d.gltf["nodes"][1]["children"] = {0};
    d.gltf["skins"][0]["joints"] = {1, 0};
    d.gltf["animations"][0]["channels"][0]["target"]["node"] = 0;
    const Character c = load(writeGltf("reordered.gltf", d.withEmbeddedBuffer()));
    ASSERT_EQ(c.nodes.size(), 3u);
    const int root = c.findNode("root").value();
    const int tip = c.findNode("tip").value();
    EXPECT_LT(root, tip);
    EXPECT_EQ(c.nodes[size_t(tip)].parent, root);
    EXPECT_EQ(c.skins[0].joints, (std::vector<int>{root, tip}));
    EXPECT_EQ(c.clips[0].channels[0].node, tip);
}

TEST(GltfImportHandMade, NodeMatrixIsSplitIntoTranslationRotationScale) {
    Document d = riggedTriangle();
    // Rotation of 90 degrees about z, scale 2, translation (1, 2, 3), column-major.
    d.gltf["nodes"][1].erase("translation");
    d.gltf["nodes"][1]["matrix"] = {0, 2, 0, 0, -2, 0, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1};
    const Character c = load(writeGltf("matrix.gltf", d.withEmbeddedBuffer()));
    const mfx::anim::Transform& t = c.nodes[1].rest;
    EXPECT_NEAR(glm::distance(t.translation, glm::vec3(1, 2, 3)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(t.scale, glm::vec3(2.0f)), 0.0f, 1e-6f);
    EXPECT_NEAR(std::abs(t.rotation.z), std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(std::abs(t.rotation.w), std::sqrt(0.5f), 1e-6f);
}

TEST(GltfImportHandMade, AllZeroWeightsBindToTheFirstJoint) {
    TriangleSpec spec;
    std::fill(spec.weights.begin() + 4, spec.weights.begin() + 8, 0.0f);
    const Character c =
        load(writeGltf("zero_weights.gltf", riggedTriangle(spec).withEmbeddedBuffer()));
    const mfx::anim::Primitive& p = c.meshes[0].primitives[0];
    EXPECT_EQ(p.joints[1], glm::uvec4(0));
    EXPECT_EQ(p.weights[1], glm::vec4(1, 0, 0, 0));
    EXPECT_EQ(p.weights[0], glm::vec4(0.5f, 0.5f, 0, 0));
}

TEST(GltfImportHandMade, MeshOnTwoNodesIsCopiedPerNode) {
    Document d = riggedTriangle();
    d.gltf["nodes"].push_back({{"name", "statue"}, {"mesh", 0}});
    const Character c = load(writeGltf("two_instances.gltf", d.withEmbeddedBuffer()));
    ASSERT_EQ(c.meshes.size(), 2u);
    EXPECT_EQ(c.meshes[0].primitives[0].skin, 0);
    EXPECT_EQ(c.meshes[1].name, "triangle@statue");
    EXPECT_EQ(c.meshes[1].primitives[0].skin, -1);
    EXPECT_EQ(c.meshes[1].primitives[0].node, c.findNode("statue").value());
    EXPECT_TRUE(c.meshes[1].primitives[0].joints.empty());
}

TEST(GltfImportHandMade, ExternalBufferBesideTheFileLoads) {
    const Document d = riggedTriangle();
    json gltf = d.gltf;
    gltf["buffers"] = json::array({{{"byteLength", d.bin.size()}, {"uri", "triangle.bin"}}});
    std::ofstream(outputPath("triangle.bin"), std::ios::binary)
        .write(reinterpret_cast<const char*>(d.bin.data()), std::streamsize(d.bin.size()));
    const Character c = load(writeGltf("external.gltf", gltf));
    EXPECT_EQ(c.meshes.size(), 1u);
    gltf["buffers"][0]["uri"] = "missing.bin";
    EXPECT_CONTAINS(refusal("external_missing.gltf", gltf), "missing.bin");
}

void appendU32(std::string& out, uint32_t value) {
    for (int i = 0; i < 4; ++i)
        out += char((value >> (8 * i)) & 0xFF);
}

std::string glbOf(const Document& d) {
    json gltf = d.gltf;
    gltf["buffers"] = json::array({{{"byteLength", d.bin.size()}}});
    std::string text = gltf.dump();
    while (text.size() % 4 != 0)
        text += ' ';
    std::string bin(d.bin.begin(), d.bin.end());
    while (bin.size() % 4 != 0)
        bin += '\0';
    std::string out = "glTF";
    appendU32(out, 2);
    appendU32(out, uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    appendU32(out, uint32_t(text.size()));
    out += "JSON";
    out += text;
    appendU32(out, uint32_t(bin.size()));
    out += std::string("BIN\0", 4);
    out += bin;
    return out;
}

std::string writeBytes(const std::string& name, const std::string& bytes) {
    const std::string path = outputPath(name);
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    return path;
}

TEST(GltfImportHandMade, GlbLoadsWhateverItsExtension) {
    const std::string glb = glbOf(riggedTriangle());
    for (const char* name : {"triangle.glb", "triangle_named_like_text.gltf"}) {
        const Character c = load(writeBytes(name, glb));
        EXPECT_EQ(c.skins.size(), 1u) << name;
        EXPECT_EQ(c.clips.size(), 1u) << name;
    }
}

TEST(GltfImportHandMade, TruncatedGlbIsRefusedAtEveryLength) {
    const std::string glb = glbOf(riggedTriangle());
    for (size_t length = 4; length < glb.size(); length += 7) {
        const std::string name = "truncated.glb";
        const mfx::Result<Character> result = importGltf(writeBytes(name, glb.substr(0, length)));
        ASSERT_FALSE(result.ok()) << length;
        EXPECT_NE(result.error().message.find(name), std::string::npos);
        EXPECT_EQ(result.error().message.find('\n'), std::string::npos);
    }
}

TEST(GltfImportHandMade, DeeplyNestedJsonIsRefused) {
    const std::string nesting(100000, '[');
    const std::string text = R"({"asset": {"version": "2.0"}, "extras": )" + nesting +
                             std::string(nesting.size(), ']') + "}";
    const mfx::Result<Character> result = importGltf(writeBytes("deep.gltf", text));
    ASSERT_FALSE(result.ok());
    EXPECT_CONTAINS(result.error().message, "deep.gltf: the JSON nests deeper than");
}

TEST(GltfImportHandMade, DirectoryIsRefused) {
    const mfx::Result<Character> result = importGltf(MFX_TEST_OUTPUT_DIR);
    ASSERT_FALSE(result.ok());
    EXPECT_CONTAINS(result.error().message, "not a regular file");
}

TEST(GltfImportHandMade, MissingFileNamesIt) {
    const mfx::Result<Character> result = importGltf(outputPath("no_such_file.gltf"));
    ASSERT_FALSE(result.ok());
    EXPECT_CONTAINS(result.error().message, "no_such_file.gltf");
}

} // namespace

namespace {

// --- Files that reach outside their folder, and files that ask for more than they hold ---------

// The rigged triangle with its buffer in `uri` (relative to the test's folder), whose bytes are
// also written to `written` (a path under the test output folder) so that a read would succeed.
json triangleWithBufferAt(const std::string& uri, const std::string& written) {
    const Document d = riggedTriangle();
    std::filesystem::create_directories(std::filesystem::path(written).parent_path());
    std::ofstream(written, std::ios::binary)
        .write(reinterpret_cast<const char*>(d.bin.data()), std::streamsize(d.bin.size()));
    json gltf = d.gltf;
    gltf["buffers"] = json::array({{{"byteLength", d.bin.size()}, {"uri", uri}}});
    return gltf;
}

TEST(GltfImportHandMade, BufferUriLeavingTheFolderIsRefused) {
    // Each URI names a real file of the right length outside the glTF's folder: before, it was
    // read and its bytes used as vertices.
    const std::string outside = std::string(MFX_TEST_OUTPUT_DIR) + "/outside.bin";
    const std::string leaves = "leads outside the glTF file's folder";
    for (const auto& [name, uri] : std::vector<std::pair<std::string, std::string>>{
             {"dots.gltf", "../outside.bin"},
             {"percent.gltf", "%2e%2e/outside.bin"},
             {"percent_slash.gltf", "..%2Foutside.bin"},
             {"inner_dots.gltf", "sub/../../outside.bin"},
             {"absolute.gltf", outside},
         }) {
        const std::string message = refusal(name, triangleWithBufferAt(uri, outside));
        EXPECT_CONTAINS(message, "buffers[0].uri: \"" + uri + "\" " + leaves);
    }
}

TEST(GltfImportHandMade, BufferThroughALinkOutOfTheFolderIsRefused) {
    const std::string outside = std::string(MFX_TEST_OUTPUT_DIR) + "/outside_linked.bin";
    json gltf = triangleWithBufferAt("linked.bin", outside);
    std::filesystem::remove(outputPath("linked.bin"));
    std::filesystem::create_symlink(outside, outputPath("linked.bin"));
    EXPECT_CONTAINS(refusal("linked.gltf", gltf), "buffers[0].uri: \"linked.bin\" leads outside");
}

TEST(GltfImportHandMade, BufferInASubfolderLoads) {
    json gltf = triangleWithBufferAt("sub/inner.bin", outputPath("sub/inner.bin"));
    EXPECT_EQ(load(writeGltf("subfolder.gltf", gltf)).meshes.size(), 1u);
    gltf["buffers"][0]["uri"] = "sub%2Finner.bin"; // percent-encoded, still inside
    EXPECT_EQ(load(writeGltf("subfolder_encoded.gltf", gltf)).meshes.size(), 1u);
}

TEST(GltfImportHandMade, ImageUriLeavingTheFolderIsRefused) {
    // Images are never decoded, but tinygltf reads their bytes: the same rule holds.
    json gltf = riggedTriangle().withEmbeddedBuffer();
    gltf["images"] = json::array({{{"uri", "../../../../../../etc/passwd"}}});
    EXPECT_CONTAINS(refusal("image_outside.gltf", gltf),
                    "images[0].uri: \"../../../../../../etc/passwd\" leads outside");
}

TEST(GltfImportHandMade, ZeroAccessorCopiedByManyNodesPassesTheVertexBudget) {
    // A kilobyte of JSON: one accessor of 2.1 million zeros without a bufferView (the most one may
    // hold is 16 million), its mesh instanced by 4 nodes: 8.4 million vertices, past the import's
    // 4 million. Before, each copy was made in full; with more primitives and nodes, tens of GB.
    json gltf = {{"asset", {{"version", "2.0"}}}};
    gltf["accessors"] =
        json::array({{{"componentType", kFloat}, {"type", "VEC3"}, {"count", 2100000}}});
    gltf["meshes"] = json::array({{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}});
    gltf["nodes"] = json::array();
    for (int n = 0; n < 4; ++n)
        gltf["nodes"].push_back({{"mesh", 0}});
    EXPECT_CONTAINS(refusal("zero_copies.gltf", gltf),
                    "meshes[0]: the file's meshes (a copy for each node using one) hold more than "
                    "4194304 vertices in all (the import's limit)");
}

TEST(GltfImportHandMade, ZeroAccessorReadByManyPrimitivesPassesTheVertexBudget) {
    // One mesh of 1000 primitives, each with the same 2.1 million zeros as its POSITION: 2.1
    // billion vertices asked for by 20 KB of JSON. Charged as each primitive is read, the third
    // passes the import's 4 million (before, the whole mesh was read first: 200 GB).
    json gltf = {{"asset", {{"version", "2.0"}}}};
    gltf["accessors"] =
        json::array({{{"componentType", kFloat}, {"type", "VEC3"}, {"count", 2100000}}});
    json primitives = json::array();
    for (int p = 0; p < 1000; ++p)
        primitives.push_back({{"attributes", {{"POSITION", 0}}}});
    gltf["meshes"] = json::array({{{"primitives", primitives}}});
    EXPECT_CONTAINS(refusal("zero_primitives.gltf", gltf),
                    "meshes[0].primitives[1]: the file's meshes (a copy for each node using one) "
                    "hold more than 4194304 vertices in all (the import's limit)");
}

} // namespace
