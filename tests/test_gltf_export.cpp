// The glTF exporter: the built-in fighter written out loads back through the importer as the same
// character (skeleton, clips, meshes, skinned positions), and the file is structurally valid glTF
// 2.0 as read by an independent reader (tests/gltf_raw.h): every accessor in bounds, counts and
// indices consistent, the bounds glTF requires present and right.
#include "core/anim/gltf_export.h"

#include "core/anim/fighter.h"
#include "core/anim/gltf_import.h"
#include "core/anim/sampling.h"
#include "core/anim/skinning.h"
#include "tests/gltf_raw.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>
#include <optional>
#include <set>
#include <string>

namespace {

using mfx::anim::Character;
using nlohmann::json;

std::string outputPath(const std::string& name) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/gltf_export";
    std::filesystem::create_directories(dir);
    return dir + "/" + name;
}

std::string exportFighter(const std::string& name) {
    const std::string path = outputPath(name);
    const mfx::Status written = mfx::anim::exportGltf(mfx::anim::makeFighter(), path);
    EXPECT_TRUE(written.ok()) << written.error().message;
    return path;
}

Character importBack(const std::string& path) {
    mfx::Result<Character> loaded = mfx::anim::importGltf(path);
    EXPECT_TRUE(loaded.ok()) << loaded.error().message;
    return loaded ? std::move(loaded).value() : Character{};
}

// The importer renormalises quaternions (the one repair glTF allows); an already unit quaternion
// may move by an ulp or so.
constexpr float kRenormalised = 1e-6f;

void expectNear(const glm::vec4& a, const glm::vec4& b, float tolerance, const std::string& what) {
    EXPECT_LE(glm::length(a - b), tolerance) << what;
}

TEST(GltfExport, FighterSkeletonComesBackIdentical) {
    const Character original = mfx::anim::makeFighter();
    const Character back = importBack(exportFighter("skeleton.glb"));
    // Every node in the same order, plus one root node per skinned mesh to carry it.
    ASSERT_EQ(back.nodes.size(), original.nodes.size() + original.meshes.size());
    for (size_t i = 0; i < original.nodes.size(); ++i) {
        const mfx::anim::Node& a = original.nodes[i];
        const mfx::anim::Node& b = back.nodes[i];
        EXPECT_EQ(a.name, b.name) << i;
        EXPECT_EQ(a.parent, b.parent) << a.name;
        EXPECT_EQ(a.rest.translation, b.rest.translation) << a.name;
        EXPECT_EQ(a.rest.scale, b.rest.scale) << a.name;
        expectNear(
            glm::vec4(a.rest.rotation.x, a.rest.rotation.y, a.rest.rotation.z, a.rest.rotation.w),
            glm::vec4(b.rest.rotation.x, b.rest.rotation.y, b.rest.rotation.z, b.rest.rotation.w),
            kRenormalised, a.name);
    }
    for (size_t m = 0; m < original.meshes.size(); ++m) {
        EXPECT_EQ(back.nodes[original.nodes.size() + m].name, original.meshes[m].name);
        EXPECT_EQ(back.nodes[original.nodes.size() + m].parent, -1);
    }

    ASSERT_EQ(back.skins.size(), original.skins.size());
    for (size_t s = 0; s < original.skins.size(); ++s) {
        EXPECT_EQ(back.skins[s].name, original.skins[s].name);
        EXPECT_EQ(back.skins[s].joints, original.skins[s].joints);
        EXPECT_EQ(back.skins[s].inverseBind, original.skins[s].inverseBind);
    }
}

TEST(GltfExport, FighterClipsComeBackIdentical) {
    const Character original = mfx::anim::makeFighter();
    const Character back = importBack(exportFighter("clips.glb"));
    ASSERT_EQ(back.clips.size(), original.clips.size());
    for (size_t c = 0; c < original.clips.size(); ++c) {
        const mfx::anim::Clip& a = original.clips[c];
        const mfx::anim::Clip& b = back.clips[c];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.duration, b.duration) << a.name;
        ASSERT_EQ(a.channels.size(), b.channels.size()) << a.name;
        for (size_t k = 0; k < a.channels.size(); ++k) {
            const std::string where = a.name + " channel " + std::to_string(k);
            EXPECT_EQ(a.channels[k].node, b.channels[k].node) << where;
            EXPECT_EQ(a.channels[k].path, b.channels[k].path) << where;
            EXPECT_EQ(a.channels[k].interpolation, b.channels[k].interpolation) << where;
            EXPECT_EQ(a.channels[k].times, b.channels[k].times) << where;
            ASSERT_EQ(a.channels[k].values.size(), b.channels[k].values.size()) << where;
            for (size_t v = 0; v < a.channels[k].values.size(); ++v) {
                glm::vec4 expected = a.channels[k].values[v];
                if (a.channels[k].path != mfx::anim::Path::Rotation) expected.w = 0.0f;
                glm::vec4 got = b.channels[k].values[v];
                if (b.channels[k].path != mfx::anim::Path::Rotation) got.w = 0.0f;
                expectNear(expected, got, kRenormalised, where);
            }
        }
    }
}

TEST(GltfExport, FighterMeshesComeBackIdentical) {
    const Character original = mfx::anim::makeFighter();
    const Character back = importBack(exportFighter("meshes.glb"));
    ASSERT_EQ(back.meshes.size(), original.meshes.size());
    for (size_t m = 0; m < original.meshes.size(); ++m) {
        const mfx::anim::Mesh& a = original.meshes[m];
        const mfx::anim::Mesh& b = back.meshes[m];
        EXPECT_EQ(a.name, b.name);
        ASSERT_EQ(a.primitives.size(), b.primitives.size()) << a.name;
        for (size_t p = 0; p < a.primitives.size(); ++p) {
            const mfx::anim::Primitive& pa = a.primitives[p];
            const mfx::anim::Primitive& pb = b.primitives[p];
            const std::string where = a.name + " primitive " + std::to_string(p);
            EXPECT_EQ(pa.positions, pb.positions) << where;
            EXPECT_EQ(pa.uvs, pb.uvs) << where;
            EXPECT_EQ(pa.joints, pb.joints) << where;
            EXPECT_EQ(pa.indices, pb.indices) << where;
            EXPECT_EQ(pa.baseColor, pb.baseColor) << where;
            EXPECT_EQ(pa.skin, pb.skin) << where;
            EXPECT_EQ(pa.node, pb.node) << where;
            ASSERT_EQ(pa.normals.size(), pb.normals.size()) << where;
            ASSERT_EQ(pa.weights.size(), pb.weights.size()) << where;
            float normalError = 0.0f, weightError = 0.0f;
            for (size_t v = 0; v < pa.normals.size(); ++v)
                normalError = std::max(normalError, glm::length(pa.normals[v] - pb.normals[v]));
            for (size_t v = 0; v < pa.weights.size(); ++v)
                weightError = std::max(weightError, glm::length(pa.weights[v] - pb.weights[v]));
            // Both renormalised on import (normals to unit length, weights to sum 1).
            EXPECT_LE(normalError, kRenormalised) << where;
            EXPECT_LE(weightError, kRenormalised) << where;
        }
    }
    // The sword stays its own mesh, every vertex bound to the right hand alone.
    const mfx::anim::Mesh* sword = back.findMesh("sword");
    ASSERT_NE(sword, nullptr);
    const std::optional<int> hand = back.findNode("hand_r");
    ASSERT_TRUE(hand.has_value());
    for (const mfx::anim::Primitive& p : sword->primitives)
        for (size_t v = 0; v < p.joints.size(); ++v) {
            ASSERT_EQ(back.skins[size_t(p.skin)].joints[p.joints[v].x], *hand);
            ASSERT_EQ(p.weights[v].x, 1.0f);
        }
}

TEST(GltfExport, FighterSkinnedPositionsAgreeAtTenTimesOfEveryClip) {
    const Character original = mfx::anim::makeFighter();
    const Character back = importBack(exportFighter("skinned.glb"));
    ASSERT_EQ(back.clips.size(), original.clips.size());
    float worst = 0.0f;
    size_t vertices = 0;
    for (size_t c = 0; c < original.clips.size(); ++c)
        for (int i = 0; i < 10; ++i) {
            const float t = original.clips[c].duration * float(i) / 9.0f;
            const mfx::anim::Pose a =
                mfx::anim::samplePose(original, &original.clips[c], t, mfx::anim::Wrap::Clamp);
            const mfx::anim::Pose b =
                mfx::anim::samplePose(back, &back.clips[c], t, mfx::anim::Wrap::Clamp);
            for (size_t m = 0; m < original.meshes.size(); ++m)
                for (size_t p = 0; p < original.meshes[m].primitives.size(); ++p) {
                    const auto sa =
                        mfx::anim::skinPrimitive(original, original.meshes[m].primitives[p], a);
                    const auto sb = mfx::anim::skinPrimitive(back, back.meshes[m].primitives[p], b);
                    ASSERT_EQ(sa.size(), sb.size());
                    for (size_t v = 0; v < sa.size(); ++v)
                        worst = std::max(worst, glm::length(sa[v].position - sb[v].position));
                    vertices += sa.size();
                }
        }
    std::printf("round trip: %zu skinned vertices compared, worst distance %.3g m\n", vertices,
                double(worst));
    // Float precision of a 1.8 m figure: the renormalised weights and quaternions move positions
    // by a few ulps (~1e-7 m each).
    EXPECT_LE(worst, 1e-5f);
}

// --- Structure, read back without the importer -------------------------------------------------

size_t arrayCount(const json& doc, const char* key) {
    return doc.contains(key) ? doc[key].size() : 0;
}

void expectValidStructure(const std::string& path) {
    SCOPED_TRACE(path);
    const mfx::test::RawGltf raw = mfx::test::readRawGltf(path);
    const json& doc = raw.doc;
    EXPECT_EQ(doc["asset"]["version"], "2.0");

    // Buffers and views: every view inside its buffer; the declared length is what is there (a
    // GLB's BIN chunk may pad up to 3 bytes).
    ASSERT_EQ(raw.buffers.size(), arrayCount(doc, "buffers"));
    for (size_t b = 0; b < raw.buffers.size(); ++b) {
        const size_t declared = doc["buffers"][b]["byteLength"];
        EXPECT_LE(declared, raw.buffers[b].size()) << "buffers[" << b << "]";
        EXPECT_LE(raw.buffers[b].size(), declared + 3) << "buffers[" << b << "]";
    }
    for (size_t v = 0; v < arrayCount(doc, "bufferViews"); ++v) {
        const json& view = doc["bufferViews"][v];
        const size_t buffer = view["buffer"];
        ASSERT_LT(buffer, raw.buffers.size()) << "bufferViews[" << v << "]";
        EXPECT_LE(view.value("byteOffset", size_t(0)) + view["byteLength"].get<size_t>(),
                  doc["buffers"][buffer]["byteLength"].get<size_t>())
            << "bufferViews[" << v << "]";
    }
    // Every accessor reads in bounds (readAccessor checks each byte range).
    std::vector<std::vector<double>> accessors;
    for (size_t a = 0; a < arrayCount(doc, "accessors"); ++a)
        accessors.push_back(mfx::test::readAccessor(raw, a));

    // Nodes: children in range, at most one parent, the scene lists exactly the roots.
    const size_t nodeCount = arrayCount(doc, "nodes");
    std::vector<int> parents(nodeCount, -1);
    for (size_t n = 0; n < nodeCount; ++n)
        for (const json& child : doc["nodes"][n].value("children", json::array())) {
            ASSERT_LT(child.get<size_t>(), nodeCount);
            EXPECT_EQ(parents[child.get<size_t>()], -1) << "node " << child << " has two parents";
            parents[child.get<size_t>()] = int(n);
        }
    std::set<size_t> roots;
    for (size_t n = 0; n < nodeCount; ++n)
        if (parents[n] < 0) roots.insert(n);
    std::set<size_t> sceneNodes;
    for (const json& n : doc["scenes"][doc["scene"].get<size_t>()]["nodes"])
        sceneNodes.insert(n.get<size_t>());
    EXPECT_EQ(sceneNodes, roots);

    // Skins: one inverse bind matrix per joint; joints are nodes.
    for (size_t s = 0; s < arrayCount(doc, "skins"); ++s) {
        const json& skin = doc["skins"][s];
        for (const json& joint : skin["joints"])
            EXPECT_LT(joint.get<size_t>(), nodeCount);
        const json& ibm = doc["accessors"][skin["inverseBindMatrices"].get<size_t>()];
        EXPECT_EQ(ibm["type"], "MAT4");
        EXPECT_EQ(ibm["count"].get<size_t>(), skin["joints"].size()) << "skins[" << s << "]";
    }

    // Meshes: attributes of one count, POSITION bounds right, indices and joints in range.
    for (size_t n = 0; n < nodeCount; ++n) {
        const json& node = doc["nodes"][n];
        if (!node.contains("mesh")) continue;
        const json& mesh = doc["meshes"][node["mesh"].get<size_t>()];
        const size_t jointCount =
            node.contains("skin") ? doc["skins"][node["skin"].get<size_t>()]["joints"].size() : 0;
        for (const json& primitive : mesh["primitives"]) {
            const json& attributes = primitive["attributes"];
            const size_t position = attributes["POSITION"];
            const size_t vertices = doc["accessors"][position]["count"];
            for (const auto& [name, index] : attributes.items())
                EXPECT_EQ(doc["accessors"][index.get<size_t>()]["count"].get<size_t>(), vertices)
                    << name;
            const std::vector<double>& p = accessors[position];
            for (int c = 0; c < 3; ++c) {
                double low = p[size_t(c)], high = p[size_t(c)];
                for (size_t v = 0; v < vertices; ++v) {
                    low = std::min(low, p[v * 3 + size_t(c)]);
                    high = std::max(high, p[v * 3 + size_t(c)]);
                }
                EXPECT_EQ(doc["accessors"][position]["min"][size_t(c)].get<double>(), low);
                EXPECT_EQ(doc["accessors"][position]["max"][size_t(c)].get<double>(), high);
            }
            if (primitive.contains("indices")) {
                const std::vector<double>& indices = accessors[primitive["indices"].get<size_t>()];
                EXPECT_EQ(indices.size() % 3, 0u);
                for (double i : indices)
                    ASSERT_LT(i, double(vertices));
            }
            if (attributes.contains("JOINTS_0")) {
                EXPECT_GT(jointCount, 0u) << "a skinned primitive on a node with a skin";
                for (double j : accessors[attributes["JOINTS_0"].get<size_t>()])
                    ASSERT_LT(j, double(jointCount));
                const std::vector<double>& w = accessors[attributes["WEIGHTS_0"].get<size_t>()];
                for (size_t v = 0; v < vertices; ++v) {
                    EXPECT_NEAR(w[v * 4] + w[v * 4 + 1] + w[v * 4 + 2] + w[v * 4 + 3], 1.0, 2e-7);
                }
            }
            if (primitive.contains("material")) {
                EXPECT_LT(primitive["material"].get<size_t>(), arrayCount(doc, "materials"));
            }
        }
    }

    // Animations: times increase with their min/max; outputs hold one value per key (three for
    // CUBICSPLINE); targets are nodes.
    for (size_t a = 0; a < arrayCount(doc, "animations"); ++a) {
        const json& animation = doc["animations"][a];
        for (const json& channel : animation["channels"]) {
            ASSERT_LT(channel["sampler"].get<size_t>(), animation["samplers"].size());
            EXPECT_LT(channel["target"]["node"].get<size_t>(), nodeCount);
        }
        for (const json& sampler : animation["samplers"]) {
            const std::vector<double>& times = accessors[sampler["input"].get<size_t>()];
            const json& input = doc["accessors"][sampler["input"].get<size_t>()];
            for (size_t k = 1; k < times.size(); ++k)
                EXPECT_LT(times[k - 1], times[k]);
            EXPECT_EQ(input["min"][0].get<double>(), times.front());
            EXPECT_EQ(input["max"][0].get<double>(), times.back());
            const size_t perKey = sampler.value("interpolation", "LINEAR") == "CUBICSPLINE" ? 3 : 1;
            EXPECT_EQ(doc["accessors"][sampler["output"].get<size_t>()]["count"].get<size_t>(),
                      times.size() * perKey);
        }
    }
}

TEST(GltfExport, GlbStructureIsValid) {
    expectValidStructure(exportFighter("structure.glb"));
}

TEST(GltfExport, GltfWithEmbeddedBufferIsValidAndLoadsTheSame) {
    const std::string text = exportFighter("structure.gltf");
    expectValidStructure(text);
    const Character fromText = importBack(text);
    const Character fromGlb = importBack(exportFighter("compare.glb"));
    ASSERT_EQ(fromText.meshes.size(), fromGlb.meshes.size());
    for (size_t m = 0; m < fromText.meshes.size(); ++m)
        for (size_t p = 0; p < fromText.meshes[m].primitives.size(); ++p)
            EXPECT_EQ(fromText.meshes[m].primitives[p].positions,
                      fromGlb.meshes[m].primitives[p].positions);
    ASSERT_EQ(fromText.clips.size(), fromGlb.clips.size());
    for (size_t c = 0; c < fromText.clips.size(); ++c)
        EXPECT_EQ(fromText.clips[c].duration, fromGlb.clips[c].duration);
}

// --- What cannot be exported ---------------------------------------------------------------------

TEST(GltfExport, MeshWhosePrimitivesArePlacedDifferentlyIsRefused) {
    Character fighter = mfx::anim::makeFighter();
    mfx::anim::Mesh& body = fighter.meshes[0];
    ASSERT_GE(body.primitives.size(), 2u);
    mfx::anim::Primitive rigid = body.primitives[0];
    rigid.skin = -1;
    rigid.joints.clear();
    rigid.weights.clear();
    rigid.node = 0;
    body.primitives[1] = rigid;
    const mfx::Status written = mfx::anim::exportGltf(fighter, outputPath("mixed.glb"));
    ASSERT_FALSE(written.ok());
    EXPECT_NE(written.error().message.find("meshes[0]"), std::string::npos)
        << written.error().message;
    EXPECT_NE(written.error().message.find("placed differently"), std::string::npos)
        << written.error().message;
}

TEST(GltfExport, BrokenCharacterIsRefusedNamingTheElement) {
    Character fighter = mfx::anim::makeFighter();
    fighter.skins[0].inverseBind.pop_back();
    const mfx::Status written = mfx::anim::exportGltf(fighter, outputPath("broken.glb"));
    ASSERT_FALSE(written.ok());
    EXPECT_NE(written.error().message.find("skins[0]"), std::string::npos)
        << written.error().message;
}

TEST(GltfExport, UnwritablePathIsRefusedNamingIt) {
    const mfx::Status written =
        mfx::anim::exportGltf(mfx::anim::makeFighter(), "/nonexistent/dir/fighter.glb");
    ASSERT_FALSE(written.ok());
    EXPECT_NE(written.error().message.find("/nonexistent/dir/fighter.glb"), std::string::npos)
        << written.error().message;
    const mfx::Status directory =
        mfx::anim::exportGltf(mfx::anim::makeFighter(), std::string(MFX_TEST_OUTPUT_DIR));
    EXPECT_FALSE(directory.ok());
}

} // namespace
