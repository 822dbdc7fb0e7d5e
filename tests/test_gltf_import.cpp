// The glTF importer: the third-party characters in ../shared/assets load as their README
// describes, and every file of the malformed corpus in ../shared/gltf-bad loads (in bounds) or is
// refused with one line naming the file. Hand-made files: test_gltf_import_hand_made.cpp.
#include "core/anim/gltf_import.h"

#include "core/anim/sampling.h"
#include "core/anim/skinning.h"
#include "tests/gltf_load.h"
#include "tests/gltf_raw.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace {

using mfx::anim::Character;
using mfx::anim::importGltf;
using mfx::test::expectValid;
using mfx::test::load;
using nlohmann::json;

const std::string kShared = std::string(MFX_SOURCE_DIR) + "/../shared";

std::string assetPath(const std::string& name) {
    return kShared + "/assets/" + name;
}

// The clip durations the file itself states: the largest `max` of each animation's input
// accessors, read with a plain JSON parser rather than the importer.
std::vector<float> statedClipDurations(const std::string& path) {
    std::ifstream in(path);
    const json gltf = json::parse(in);
    std::vector<float> durations;
    for (const json& animation : gltf["animations"]) {
        float duration = 0.0f;
        for (const json& sampler : animation["samplers"])
            duration = std::max(
                duration, gltf["accessors"][sampler["input"].get<size_t>()]["max"][0].get<float>());
        durations.push_back(duration);
    }
    return durations;
}

struct AssetExpectation {
    const char* file;
    size_t joints;
    size_t firstPrimitiveVertices;
    size_t firstPrimitiveIndices;
};

void expectAsset(const AssetExpectation& expected) {
    const Character character = load(assetPath(expected.file));
    ASSERT_EQ(character.skins.size(), 1u);
    EXPECT_EQ(character.skins[0].joints.size(), expected.joints);
    ASSERT_FALSE(character.meshes.empty());
    ASSERT_FALSE(character.meshes[0].primitives.empty());
    const mfx::anim::Primitive& primitive = character.meshes[0].primitives[0];
    EXPECT_EQ(primitive.positions.size(), expected.firstPrimitiveVertices);
    EXPECT_EQ(primitive.indices.size(), expected.firstPrimitiveIndices);
    EXPECT_EQ(primitive.skin, 0);
    EXPECT_EQ(primitive.joints.size(), primitive.positions.size());
    const std::vector<float> durations = statedClipDurations(assetPath(expected.file));
    ASSERT_EQ(character.clips.size(), durations.size());
    for (size_t i = 0; i < durations.size(); ++i)
        EXPECT_FLOAT_EQ(character.clips[i].duration, durations[i]) << "clip " << i;
}

TEST(GltfImportAssets, SimpleSkin) {
    expectAsset({"SimpleSkin.gltf", 2, 10, 24});
}
TEST(GltfImportAssets, RiggedSimple) {
    expectAsset({"RiggedSimple.gltf", 2, 160, 564});
}
TEST(GltfImportAssets, RiggedFigure) {
    expectAsset({"RiggedFigure.gltf", 19, 370, 768});
}

TEST(GltfImportAssets, RiggedFigureHas57ChannelsOfOneAndAQuarterSeconds) {
    const Character character = load(assetPath("RiggedFigure.gltf"));
    ASSERT_EQ(character.clips.size(), 1u);
    EXPECT_EQ(character.clips[0].channels.size(), 57u);
    EXPECT_FLOAT_EQ(character.clips[0].duration, 1.25f);
}

TEST(GltfImportAssets, NamesAreKeptAndMissingOnesMadeFromIndices) {
    const Character rigged = load(assetPath("RiggedSimple.gltf"));
    EXPECT_NE(rigged.findMesh("Cylinder"), nullptr);
    EXPECT_TRUE(rigged.findNode("Bone").has_value());
    EXPECT_TRUE(rigged.findNode("Bone.001").has_value());
    EXPECT_NE(rigged.findClip("clip_0"), nullptr);
    EXPECT_EQ(rigged.name, "RiggedSimple");

    const Character simple = load(assetPath("SimpleSkin.gltf"));
    EXPECT_NE(simple.findMesh("mesh_0"), nullptr);
    for (const char* node : {"node_0", "node_1", "node_2"})
        EXPECT_TRUE(simple.findNode(node).has_value()) << node;
}

TEST(GltfImportAssets, RotationsAreUnitAndWeightsSumToOne) {
    const Character character = load(assetPath("RiggedFigure.gltf"));
    for (const mfx::anim::Channel& channel : character.clips[0].channels)
        if (channel.path == mfx::anim::Path::Rotation) {
            for (const glm::vec4& q : channel.values)
                EXPECT_NEAR(glm::length(q), 1.0f, 1e-5f);
        }
    for (const glm::vec4& w : character.meshes[0].primitives[0].weights)
        EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 1e-5f);
    for (const glm::vec3& n : character.meshes[0].primitives[0].normals)
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
}

// --- One skinned vertex of RiggedFigure, computed independently -----------------------------
//
// The reference below reads the file with tests/gltf_raw.h (not the importer), evaluates the
// LINEAR channels itself in double precision (lerp; slerp taking the shorter arc, glTF 2.0
// Appendix "Interpolation"), walks the node hierarchy from the children lists, and skins with the
// specification's formula sum_i w_i * world(joint_i) * inverseBind_i * p.

struct RawPose {
    std::vector<glm::dmat4> world; // per node of the file, in the file's order
};

glm::dquat rawSlerp(glm::dquat a, glm::dquat b, double u) {
    double d = glm::dot(a, b);
    if (d < 0.0) {
        b = -b;
        d = -d;
    }
    if (d > 0.9999995) return glm::normalize(a * (1.0 - u) + b * u);
    const double theta = std::acos(d);
    return glm::normalize(a * (std::sin((1.0 - u) * theta) / std::sin(theta)) +
                          b * (std::sin(u * theta) / std::sin(theta)));
}

RawPose rawPose(const mfx::test::RawGltf& raw, double time) {
    const json& nodes = raw.doc["nodes"];
    const size_t n = nodes.size();
    std::vector<glm::dvec3> translation(n, glm::dvec3(0.0)), scale(n, glm::dvec3(1.0));
    std::vector<glm::dquat> rotation(n, glm::dquat(1.0, 0.0, 0.0, 0.0));
    std::vector<bool> hasMatrix(n, false);
    std::vector<glm::dmat4> matrix(n, glm::dmat4(1.0));
    for (size_t i = 0; i < n; ++i) {
        const json& node = nodes[i];
        if (node.contains("matrix")) {
            hasMatrix[i] = true;
            for (int c = 0; c < 16; ++c)
                matrix[i][c / 4][c % 4] = node["matrix"][size_t(c)];
        }
        if (node.contains("translation"))
            for (int c = 0; c < 3; ++c)
                translation[i][c] = node["translation"][size_t(c)];
        if (node.contains("scale"))
            for (int c = 0; c < 3; ++c)
                scale[i][c] = node["scale"][size_t(c)];
        if (node.contains("rotation")) {
            const json& r = node["rotation"];
            rotation[i] = glm::dquat(r[3].get<double>(), r[0].get<double>(), r[1].get<double>(),
                                     r[2].get<double>());
        }
    }
    const json& animation = raw.doc["animations"][0];
    for (const json& channel : animation["channels"]) {
        const json& sampler = animation["samplers"][channel["sampler"].get<size_t>()];
        EXPECT_EQ(sampler.value("interpolation", "LINEAR"), "LINEAR");
        const std::vector<double> times = mfx::test::readAccessor(raw, sampler["input"]);
        const std::vector<double> values = mfx::test::readAccessor(raw, sampler["output"]);
        const size_t node = channel["target"]["node"];
        const std::string path = channel["target"]["path"];
        const size_t width = path == "rotation" ? 4 : 3;
        size_t k = 0;
        while (k + 1 < times.size() && times[k + 1] <= time)
            ++k;
        const size_t k1 = std::min(k + 1, times.size() - 1);
        const double u =
            k1 == k ? 0.0 : std::clamp((time - times[k]) / (times[k1] - times[k]), 0.0, 1.0);
        const double* a = &values[k * width];
        const double* b = &values[k1 * width];
        if (path == "rotation") {
            rotation[node] =
                rawSlerp(glm::dquat(a[3], a[0], a[1], a[2]), glm::dquat(b[3], b[0], b[1], b[2]), u);
        } else {
            glm::dvec3 v;
            for (int c = 0; c < 3; ++c)
                v[c] = a[c] * (1.0 - u) + b[c] * u;
            (path == "translation" ? translation[node] : scale[node]) = v;
        }
    }
    std::vector<int> parent(n, -1);
    for (size_t i = 0; i < n; ++i)
        for (const json& child : nodes[i].value("children", json::array()))
            parent[child.get<size_t>()] = int(i);
    RawPose pose;
    pose.world.assign(n, glm::dmat4(1.0));
    std::vector<bool> done(n, false);
    // Repeated passes: a node's world is set once its parent's is (the hierarchy is a forest).
    for (size_t pass = 0; pass < n; ++pass)
        for (size_t i = 0; i < n; ++i) {
            if (done[i] || (parent[i] >= 0 && !done[size_t(parent[i])])) continue;
            glm::dmat4 local = matrix[i];
            if (!hasMatrix[i]) {
                local = glm::translate(glm::dmat4(1.0), translation[i]) *
                        glm::mat4_cast(rotation[i]) * glm::scale(glm::dmat4(1.0), scale[i]);
            }
            pose.world[i] = parent[i] < 0 ? local : pose.world[size_t(parent[i])] * local;
            done[i] = true;
        }
    return pose;
}

TEST(GltfImportAssets, RiggedFigureSkinnedVerticesMatchTheRawAccessors) {
    const std::string path = assetPath("RiggedFigure.gltf");
    const mfx::test::RawGltf raw = mfx::test::readRawGltf(path);
    const double time = 0.61; // between keys
    const RawPose pose = rawPose(raw, time);

    const json& primitive = raw.doc["meshes"][0]["primitives"][0];
    const json& attributes = primitive["attributes"];
    const std::vector<double> positions = mfx::test::readAccessor(raw, attributes["POSITION"]);
    const std::vector<double> joints = mfx::test::readAccessor(raw, attributes["JOINTS_0"]);
    const std::vector<double> weights = mfx::test::readAccessor(raw, attributes["WEIGHTS_0"]);
    const json& skin = raw.doc["skins"][0];
    const std::vector<double> inverseBind =
        mfx::test::readAccessor(raw, skin["inverseBindMatrices"]);
    auto rawSkinned = [&](size_t v) {
        glm::dvec4 sum(0.0);
        double total = 0.0;
        for (size_t i = 0; i < 4; ++i) {
            const double w = weights[v * 4 + i];
            if (w == 0.0) continue;
            const size_t j = size_t(joints[v * 4 + i]);
            glm::dmat4 ibm;
            for (int c = 0; c < 16; ++c)
                ibm[c / 4][c % 4] = inverseBind[j * 16 + size_t(c)];
            const glm::dmat4 m = pose.world[skin["joints"][j].get<size_t>()] * ibm;
            sum += w * (m * glm::dvec4(positions[v * 3], positions[v * 3 + 1], positions[v * 3 + 2],
                                       1.0));
            total += w;
        }
        return glm::dvec3(sum) / total;
    };

    // The vertex with the most influences (linear blend skinning, the specification's formula),
    // and the first vertex bound to one joint alone that the clip moves (dual quaternion skinning
    // must agree with it there).
    size_t blended = 0, single = SIZE_MAX;
    int most = 0;
    const size_t vertexCount = positions.size() / 3;
    for (size_t v = 0; v < vertexCount; ++v) {
        int influences = 0;
        for (size_t i = 0; i < 4; ++i)
            influences += weights[v * 4 + i] > 0.0 ? 1 : 0;
        if (influences > most) {
            most = influences;
            blended = v;
        }
        const glm::dvec3 rest(positions[v * 3], positions[v * 3 + 1], positions[v * 3 + 2]);
        if (single == SIZE_MAX && influences == 1 && glm::length(rawSkinned(v) - rest) > 0.05)
            single = v;
    }
    ASSERT_GE(most, 3);
    ASSERT_NE(single, SIZE_MAX);

    const Character character = load(path);
    ASSERT_EQ(character.clips.size(), 1u);
    const mfx::anim::Pose ours =
        mfx::anim::samplePose(character, &character.clips[0], float(time), mfx::anim::Wrap::Clamp);
    const mfx::anim::Primitive& imported = character.meshes[0].primitives[0];
    const auto linear =
        mfx::anim::skinPrimitive(character, imported, ours, mfx::anim::SkinningMethod::Linear);
    const auto dualQuat =
        mfx::anim::skinPrimitive(character, imported, ours, mfx::anim::SkinningMethod::DualQuat);
    // Float against double over a 19-joint chain of products: a few ulps of the figure's size
    // (about 1.5 units) per step.
    const double tolerance = 1e-5;
    const glm::dvec3 expectedBlended = rawSkinned(blended);
    const glm::dvec3 expectedSingle = rawSkinned(single);
    EXPECT_LT(glm::length(glm::dvec3(linear[blended].position) - expectedBlended), tolerance)
        << "vertex " << blended << " (" << most << " joints)";
    EXPECT_LT(glm::length(glm::dvec3(linear[single].position) - expectedSingle), tolerance)
        << "vertex " << single;
    EXPECT_LT(glm::length(glm::dvec3(dualQuat[single].position) - expectedSingle), tolerance)
        << "vertex " << single << " (one joint: dual quaternion equals linear blend)";
    std::printf(
        "RiggedFigure at t=%.2f s: vertex %zu (%d joints) at (%.6f, %.6f, %.6f), vertex %zu "
        "(1 joint) at (%.6f, %.6f, %.6f)\n",
        time, blended, most, expectedBlended.x, expectedBlended.y, expectedBlended.z, single,
        expectedSingle.x, expectedSingle.y, expectedSingle.z);
}

// --- The malformed corpus --------------------------------------------------------------------

// Loads every .gltf/.glb of one folder: each loads with its invariants holding, or is refused
// with one line that names the file. Prints each outcome and the counts.
void importFolder(const std::string& folder) {
    const std::filesystem::path dir = kShared + "/gltf-bad/" + folder;
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const std::string ext = entry.path().extension().string();
        if (ext == ".gltf" || ext == ".glb") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    ASSERT_FALSE(files.empty()) << dir;
    size_t loaded = 0;
    size_t refused = 0;
    for (const std::filesystem::path& file : files) {
        const std::string name = file.filename().string();
        const mfx::Result<Character> result = importGltf(file);
        if (result) {
            ++loaded;
            expectValid(result.value());
            std::printf("  loaded   %s\n", name.c_str());
            continue;
        }
        ++refused;
        const std::string& message = result.error().message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_NE(message.find(name), std::string::npos) << message;
        EXPECT_GT(message.size(), file.string().size() + 2) << "no reason given: " << message;
        std::printf("  refused  %s\n", message.substr(dir.string().size() + 1).c_str());
    }
    std::printf("gltf-bad/%s: %zu loaded, %zu refused\n", folder.c_str(), loaded, refused);
}

TEST(GltfImportBadFiles, Accessor) {
    importFolder("accessor");
}
TEST(GltfImportBadFiles, Animation) {
    importFolder("animation");
}
TEST(GltfImportBadFiles, Buffer) {
    importFolder("buffer");
}
TEST(GltfImportBadFiles, BufferView) {
    importFolder("buffer_view");
}
TEST(GltfImportBadFiles, Glb) {
    importFolder("glb");
}
TEST(GltfImportBadFiles, Json) {
    importFolder("json");
}
TEST(GltfImportBadFiles, Mesh) {
    importFolder("mesh");
}
TEST(GltfImportBadFiles, Skin) {
    importFolder("skin");
}

} // namespace
