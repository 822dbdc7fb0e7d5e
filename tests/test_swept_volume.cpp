// The swept-volume motion blur (render/kinds/swept_volume_pass.h; Wloka and Zeleznik 1996):
// geometry only while the bound part moves, alpha falling along each joining strip from opaque to
// the trailing value for every temporal filter, the n-segment sweep following the curved path, the
// contour edges of a mesh split at its seams, and the scene file's refusals. The scenes are small
// (the fighter's sword) and run a few frames.
#include "core/gpu/commands.h"
#include "core/scene/scene.h"
#include "render/kinds/swept_volume_pass.h"
#include "sim/scene_simulation.h"
#include "tests/effect_pass_test.h"

#include <cmath>
#include <memory>
#include <string>

namespace mfx::test {
namespace {

// The sword slash (0.8 s) at 30 fps, held after its end; `effect` is the JSON of one effect.
scene::Scene swordScene(const std::string& effect, uint32_t frames = 30) {
    return clipScene("sword_slash", effect, frames);
}

constexpr uint32_t kSwingFrame = 11; // the blade at its fastest (0.37 s)

using SweptVolumeTest = EffectPassTest<render::SweptVolumePass>;

// The drawn geometry split into joining strips (they start at place 0, `quads` quads each) and
// trailing triangles (every vertex at place 1).
struct Pieces {
    std::vector<std::vector<shared::TrajectoryVertex>> strips;
    std::vector<shared::TrajectoryVertex> trailing;
};
Pieces split(const std::vector<shared::TrajectoryVertex>& vertices, uint32_t quads) {
    Pieces out;
    for (size_t k = 0; k < vertices.size();) {
        if (vertices[k].position.w == 0.0f) {
            EXPECT_LE(k + 6 * quads, vertices.size());
            out.strips.emplace_back(vertices.begin() + ptrdiff_t(k),
                                    vertices.begin() + ptrdiff_t(k + 6 * quads));
            k += 6 * quads;
        } else {
            EXPECT_LE(k + 3, vertices.size());
            out.trailing.insert(out.trailing.end(), vertices.begin() + ptrdiff_t(k),
                                vertices.begin() + ptrdiff_t(k + 3));
            k += 3;
        }
    }
    return out;
}

TEST_F(SweptVolumeTest, GeometryOnlyWhileTheBoundPartMoves) {
    for (const char* segments : {"1", "3"}) {
        SCOPED_TRACE(segments);
        start(swordScene(R"({"type": "swept_volume", "meshes": ["sword"], "segments": )" +
                         std::string(segments) + "}"));
        play(0, 0);
        EXPECT_EQ(counts().vertices, 0u) << "the first frame has no motion yet";
        play(1, kSwingFrame);
        EXPECT_GT(glm::length(counts().motion), 0.0f);
        EXPECT_GT(counts().contourEdges, 0u) << "the swinging sword has a contour";
        EXPECT_GT(counts().trailingTriangles, 0u) << "and a trailing side";
        EXPECT_GT(counts().vertices, 0u);
        play(kSwingFrame + 1, 29); // the pose is held from frame 24 on
        EXPECT_EQ(glm::length(counts().motion), 0.0f);
        EXPECT_EQ(counts().vertices, 0u) << "a still sword makes no volume";
        EXPECT_EQ(counts().contourEdges, 0u);
    }
}

TEST_F(SweptVolumeTest, NothingOutsideTheEffectsWindow) {
    start(swordScene(R"({"type": "swept_volume", "meshes": ["sword"], "start": 0.6})"));
    play(0, kSwingFrame);
    EXPECT_EQ(counts().vertices, 0u);
}

// Along each strip alpha starts opaque at the leading contour (place 0), never rises, ends at the
// trailing value (place 1) and stays at or above the floor; the trailing side has the trailing
// value (Wloka and Zeleznik 1996, Sec. 3.4).
TEST_F(SweptVolumeTest, AlphaFallsAlongEachStripForEveryFilter) {
    for (const char* filter : {"box", "ramp", "triangle", "gaussian"}) {
        SCOPED_TRACE(filter);
        start(swordScene(R"({"type": "swept_volume", "meshes": ["sword"], "colour": [1, 1, 1, 1],
            "segments": 2, "sub_samples": 3, "alpha_floor": 0.2, "filter": ")" +
                         std::string(filter) + "\"}"));
        play(0, kSwingFrame);
        const float trailing = counts().trailingAlpha;
        EXPECT_GE(trailing, 0.2f);
        EXPECT_LT(trailing, 1.0f);
        const Pieces pieces = split(pass_->geometry(0), 2 * 3);
        ASSERT_FALSE(pieces.strips.empty());
        ASSERT_FALSE(pieces.trailing.empty());
        for (const auto& strip : pieces.strips) {
            std::vector<std::pair<float, float>> byPlace; // (place, alpha)
            for (const shared::TrajectoryVertex& v : strip)
                byPlace.emplace_back(v.position.w, v.color.a);
            std::sort(byPlace.begin(), byPlace.end());
            for (size_t k = 1; k < byPlace.size(); ++k)
                ASSERT_LE(byPlace[k].second, byPlace[k - 1].second + 1e-6f)
                    << "at place " << byPlace[k].first;
            EXPECT_FLOAT_EQ(byPlace.front().second, 1.0f);
            EXPECT_NEAR(byPlace.back().second, trailing, 1e-5f);
            EXPECT_EQ(byPlace.back().first, 1.0f);
        }
        for (const shared::TrajectoryVertex& v : pieces.trailing)
            EXPECT_NEAR(v.color.a, trailing, 1e-5f);
    }
}

// The filters shape the alpha between the ends differently: box falls linearly, ramp (the
// latest instant weighted most) falls faster at first.
TEST_F(SweptVolumeTest, TheFilterShapesTheAlpha) {
    float middle[2] = {};
    int which = 0;
    for (const char* filter : {"box", "ramp"}) {
        start(swordScene(R"({"type": "swept_volume", "meshes": ["sword"], "colour": [1, 1, 1, 1],
            "sub_samples": 2, "filter": ")" +
                         std::string(filter) + "\"}"));
        play(0, kSwingFrame);
        const Pieces pieces = split(pass_->geometry(0), 2);
        ASSERT_FALSE(pieces.strips.empty());
        const float trailing = counts().trailingAlpha;
        // Vertex 2 of the first quad lies at place 0.5.
        ASSERT_EQ(pieces.strips[0][2].position.w, 0.5f);
        middle[which++] = (pieces.strips[0][2].color.a - trailing) / (1.0f - trailing);
    }
    EXPECT_NEAR(middle[0], 0.5f, 1e-4f) << "box: half way between opaque and trailing";
    EXPECT_NEAR(middle[1], 0.25f, 1e-4f) << "ramp: (1 - s)^2";
}

// With n segments each strip runs through the recorded positions of the last n frames: on the
// sword's arc its middle leaves the straight line between its ends (Sec. 4.2).
TEST_F(SweptVolumeTest, SegmentsFollowTheCurvedPath) {
    start(swordScene(R"({"type": "swept_volume", "meshes": ["sword"], "segments": 4,
        "sub_samples": 1})"));
    play(0, kSwingFrame);
    const Pieces pieces = split(pass_->geometry(0), 4);
    ASSERT_FALSE(pieces.strips.empty());
    float largest = 0.0f;
    for (const auto& strip : pieces.strips) {
        // Vertex 0 of quad q is the first contour vertex at place q/4; vertex 5 of the last quad
        // the same vertex at place 1.
        const glm::vec3 now = glm::vec3(strip[0].position);
        const glm::vec3 then = glm::vec3(strip[6 * 3 + 5].position);
        const glm::vec3 middle = glm::vec3(strip[6 * 2].position);
        const glm::vec3 chord = then - now;
        if (glm::length(chord) < 1e-4f) continue;
        const glm::vec3 off =
            (middle - now) - chord * glm::dot(middle - now, chord) / glm::dot(chord, chord);
        largest = std::max(largest, glm::length(off) / glm::length(chord));
        EXPECT_EQ(strip[6 * 2].position.w, 0.5f);
    }
    EXPECT_GT(largest, 0.01f) << "the path bends";
}

TEST_F(SweptVolumeTest, ASceneWithoutTheEffectHasNoPass) {
    scene::Scene s = swordScene(R"({"type": "speed_lines", "meshes": ["sword"]})");
    Result<anim::Character> c = scene::loadCharacter(s);
    ASSERT_TRUE(c);
    EXPECT_TRUE(render::SweptVolumePass(ctx(), s, {&c.value(), 1}).empty());
}

// A cube whose faces have their own vertices (24, as a flat-shaded mesh has): its 12 edges and 6
// face diagonals are found across the seams, each between two triangles.
TEST(SweptVolumeEdges, FoundAcrossSeams) {
    std::vector<shared::SkinVertexIn> vertices;
    std::vector<uint32_t> triangles;
    flatShadedCube(vertices, triangles);
    const std::vector<uint32_t> edges = render::sweptVolumeEdges(vertices, triangles);
    ASSERT_EQ(edges.size(), 18u * 6u);
    for (size_t e = 0; e < edges.size(); e += 6) {
        EXPECT_NE(edges[e], edges[e + 1]);
        // Each side names the same two corners.
        EXPECT_EQ(vertices[edges[e + 2]].position, vertices[edges[e + 4]].position);
        EXPECT_EQ(vertices[edges[e + 3]].position, vertices[edges[e + 5]].position);
    }
}

// The scene file's options and refusals: one line naming the effect's key.
std::string sceneError(const std::string& effect) {
    Result<scene::Scene> s = scene::parseScene(R"({"effects": [)" + effect + "]}", "s.json");
    return s ? std::string() : s.error().message;
}

TEST(SweptVolumeScene, DefaultsAndEveryOption) {
    Result<scene::Scene> d = scene::parseScene(R"({"effects": [{"type": "swept_volume"}]})", "s");
    ASSERT_TRUE(d) << d.error().message;
    EXPECT_EQ(d.value().effects[0].name, "swept_volume#0");
    ASSERT_TRUE(d.value().effects[0].is<scene::SweptVolumeSpec>());
    const scene::SweptVolumeSpec& e = *d.value().effects[0].as<scene::SweptVolumeSpec>();
    EXPECT_EQ(e.filter, scene::SweptFilter::Ramp);
    EXPECT_EQ(e.segments, 1u);
    EXPECT_EQ(e.alphaFloor, 0.1f);
    EXPECT_EQ(e.subSamples, 4u);
    EXPECT_TRUE(e.useMeshColour);

    Result<scene::Scene> s = scene::parseScene(
        R"({"effects": [{"type": "swept_volume", "filter": "gaussian", "segments": 5,
        "alpha_floor": 0.3, "sub_samples": 2, "colour": [1, 0, 0]}]})",
        "s.json");
    ASSERT_TRUE(s) << s.error().message;
    ASSERT_TRUE(s.value().effects[0].is<scene::SweptVolumeSpec>());
    const scene::SweptVolumeSpec& o = *s.value().effects[0].as<scene::SweptVolumeSpec>();
    EXPECT_EQ(o.filter, scene::SweptFilter::Gaussian);
    EXPECT_EQ(o.segments, 5u);
    EXPECT_EQ(o.alphaFloor, 0.3f);
    EXPECT_EQ(o.subSamples, 2u);
    EXPECT_FALSE(o.useMeshColour);
}

TEST(SweptVolumeScene, RefusesBadValues) {
    EXPECT_EQ(sceneError(R"({"type": "swept_volume", "segments": 0})"),
              "s.json: effects[0].segments: 0 is outside 1..16");
    EXPECT_EQ(sceneError(R"({"type": "swept_volume", "segments": 2.5})")
                  .rfind("s.json: effects[0].segments: ", 0),
              0u);
    EXPECT_EQ(sceneError(R"({"type": "swept_volume", "alpha_floor": 1.5})"),
              "s.json: effects[0].alpha_floor: 1.5 is outside [0, 1]");
    EXPECT_EQ(sceneError(R"({"type": "swept_volume", "filter": "sinc"})"),
              "s.json: effects[0].filter: \"sinc\" is not one of: box, ramp, triangle, gaussian");
    EXPECT_EQ(sceneError(R"({"type": "swept_volume", "sub_samples": 17})"),
              "s.json: effects[0].sub_samples: 17 is outside 1..16");
}

TEST(SweptVolumeScene, RefusesKeysOfOtherEffects) {
    EXPECT_EQ(sceneError(R"({"type": "swept_volume", "segmnets": 2})")
                  .rfind("s.json: effects[0].segmnets: unknown key; keys here are: ", 0),
              0u);
    EXPECT_EQ(sceneError(R"({"type": "swept_volume", "lifetime": 4})"),
              "s.json: effects[0].lifetime: not a key of swept_volume effects");
    EXPECT_EQ(sceneError(R"({"type": "swept_volume", "taper": 1})"),
              "s.json: effects[0].taper: not a key of swept_volume effects");
    EXPECT_EQ(sceneError(R"({"type": "speed_lines", "segments": 2})"),
              "s.json: effects[0].segments: not a key of speed_lines effects");
    EXPECT_EQ(sceneError(R"({"type": "afterimage_smear", "filter": "box"})"),
              "s.json: effects[0].filter: not a key of afterimage_smear effects");
}

} // namespace
} // namespace mfx::test
