// The silhouette-of-motion blur shell (render/kinds/silhouette_shell_pass.h; Jones 2004): geometry
// only while the bound part moves, each strip attached to the live mesh, alpha falling linearly
// along it, strips fading out when their polygon leaves the silhouette, several updates a frame or
// one every few frames, normals averaged across seams, and the scene file's refusals. The scenes
// are small (the fighter's kicking leg) and run a few frames.
#include "core/gpu/commands.h"
#include "core/scene/scene.h"
#include "render/kinds/silhouette_shell_pass.h"
#include "sim/scene_simulation.h"
#include "tests/effect_pass_test.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <utility>

namespace mfx::test {
namespace {

// The roundhouse kick (0.9 s) at 30 fps, held after its end; `effect` is the JSON of one effect.
scene::Scene kickScene(const std::string& effect, uint32_t frames = 45) {
    return clipScene("roundhouse_kick", effect, frames);
}

constexpr uint32_t kKickFrame = 12;  // the leg swinging fast (0.4 s)
constexpr uint32_t kLastMoving = 27; // the clip ends at 0.9 s; the pose is held after it
const std::string kLeg = R"("bones": ["thigh_r", "shin_r", "foot_r", "toe_r"])";

using SilhouetteShellTest = EffectPassTest<render::SilhouetteShellPass>;

// The drawn triangles split into strips: a strip starts with a quad whose first vertex is at
// place 0 (the live mesh); each quad is 6 vertices.
std::vector<std::vector<shared::TrajectoryVertex>>
strips(const std::vector<shared::TrajectoryVertex>& vertices) {
    std::vector<std::vector<shared::TrajectoryVertex>> out;
    EXPECT_EQ(vertices.size() % 6, 0u);
    for (size_t k = 0; k + 5 < vertices.size(); k += 6) {
        if (vertices[k].position.w == 0.0f) out.emplace_back();
        if (out.empty()) {
            ADD_FAILURE() << "the geometry does not start with a strip's first quad";
            return out;
        }
        out.back().insert(out.back().end(), vertices.begin() + ptrdiff_t(k),
                          vertices.begin() + ptrdiff_t(k + 6));
    }
    return out;
}

TEST_F(SilhouetteShellTest, GeometryOnlyWhileTheBoundPartMoves) {
    start(kickScene("{\"type\": \"silhouette_shell\", " + kLeg + ", \"fade_out\": 3}"));
    play(0, 0);
    EXPECT_EQ(counts().vertices, 0u) << "the first frame has no motion yet";
    play(1, kKickFrame);
    EXPECT_GT(counts().silhouetteTriangles, 0u) << "the kicking leg has a silhouette of motion";
    EXPECT_GT(counts().strips, 0u);
    EXPECT_GT(counts().vertices, 0u);
    EXPECT_EQ(counts().vertices % 6, 0u);
    // Held still: no silhouette at once, and no strip once the fade-out count has passed.
    play(kKickFrame + 1, kLastMoving + 2);
    EXPECT_EQ(counts().silhouetteTriangles, 0u);
    play(kLastMoving + 3, kLastMoving + 3 + 4);
    EXPECT_EQ(counts().strips, 0u);
    EXPECT_EQ(counts().vertices, 0u) << "a still leg makes no shell";
}

TEST_F(SilhouetteShellTest, NothingOutsideTheEffectsWindow) {
    start(kickScene("{\"type\": \"silhouette_shell\", " + kLeg + ", \"start\": 1.2}"));
    play(0, kKickFrame);
    EXPECT_EQ(counts().vertices, 0u);
}

// Each strip's first vertex pair is where two vertices of the live mesh are now (Jones 2004,
// Sec. 3.2.5: the strip is connected to its polygon), with one update a frame, with several, and
// on a frame between two updates of a blur time longer than subdivisions frames.
TEST_F(SilhouetteShellTest, TheShellStaysAttachedToTheLiveMesh) {
    struct Case {
        const char* blurTime;
        uint32_t frame, updatesPerFrame, framesPerUpdate;
    };
    for (const Case& c :
         {Case{"", kKickFrame, 1, 1}, Case{", \"blur_time\": 0.1", kKickFrame, 2, 1},
          Case{", \"blur_time\": 0.6", kKickFrame + 1, 1, 3}}) {
        SCOPED_TRACE(c.blurTime);
        start(kickScene("{\"type\": \"silhouette_shell\", " + kLeg + ", \"subdivisions\": 6" +
                        std::string(c.blurTime) + "}"));
        play(0, c.frame);
        EXPECT_EQ(counts().updatesPerFrame, c.updatesPerFrame);
        EXPECT_EQ(counts().framesPerUpdate, c.framesPerUpdate);
        EXPECT_EQ(counts().updated, c.framesPerUpdate == 1);
        std::set<std::tuple<float, float, float>> live;
        for (const glm::vec3& p : pass_->livePositions(0))
            live.insert({p.x, p.y, p.z});
        const auto all = strips(pass_->geometry(0));
        ASSERT_FALSE(all.empty());
        EXPECT_EQ(all.size(), counts().strips);
        for (const auto& strip : all) {
            for (int k : {0, 1}) {
                const glm::vec4& p = strip[size_t(k)].position;
                EXPECT_EQ(p.w, 0.0f);
                EXPECT_TRUE(live.count({p.x, p.y, p.z}))
                    << "strip vertex " << k << " at (" << p.x << ", " << p.y << ", " << p.z
                    << ") is not a vertex of the live mesh";
            }
            EXPECT_NE(glm::vec3(strip[0].position), glm::vec3(strip[1].position));
        }
    }
}

// Along each strip alpha starts at the initial value times the strip's fade, falls linearly with
// the pair's place and never rises; a full strip ends at 0 (Sec. 3.2.5).
TEST_F(SilhouetteShellTest, AlphaFallsLinearlyAlongEachStrip) {
    start(kickScene("{\"type\": \"silhouette_shell\", " + kLeg +
                    ", \"colour\": [1, 1, 1, 1], \"subdivisions\": 4, \"initial_alpha\": 0.6}"));
    play(0, kKickFrame);
    const auto all = strips(pass_->geometry(0));
    ASSERT_FALSE(all.empty());
    size_t full = 0;
    for (const auto& strip : all) {
        const float fade = strip[0].color.a / 0.6f;
        EXPECT_GT(fade, 0.0f);
        EXPECT_LE(fade, 1.0f + 1e-6f);
        float previousPlace = -1.0f, previousAlpha = 2.0f;
        for (size_t q = 0; q < strip.size(); q += 6)
            for (size_t k : {0, 1, 2, 4, 5}) {
                const shared::TrajectoryVertex& v = strip[q + k];
                const float place = v.position.w;
                EXPECT_NEAR(v.color.a, 0.6f * fade * (1.0f - place), 1e-5f);
                if (place > previousPlace) {
                    EXPECT_LE(v.color.a, previousAlpha + 1e-6f);
                    previousPlace = place;
                    previousAlpha = v.color.a;
                }
            }
        EXPECT_LE(strip.size() / 6, 4u);
        if (strip.size() / 6 == 4) {
            ++full;
            EXPECT_EQ(strip.back().position.w, 1.0f);
            EXPECT_EQ(strip.back().color.a, 0.0f);
        }
    }
    EXPECT_GT(full, 0u) << "after 12 frames of motion some strips run the whole history";
}

// A polygon that loses its silhouette edge keeps drawing its strip, faded as a whole, for the
// fade-out count, then stops; with a count of 0 strips stop at once (Sec. 3.3).
TEST_F(SilhouetteShellTest, StripsFadeOutInsteadOfPopping) {
    start(kickScene("{\"type\": \"silhouette_shell\", " + kLeg +
                    ", \"colour\": [1, 1, 1, 1], \"fade_out\": 4}"));
    play(0, kKickFrame);
    EXPECT_GT(counts().fadingStrips, 0u) << "the silhouette moves over the deforming leg";
    size_t faded = 0;
    for (const auto& strip : strips(pass_->geometry(0)))
        if (strip[0].color.a < 0.8f - 1e-5f) ++faded;
    EXPECT_EQ(faded, counts().fadingStrips);
    // Held still, the strips fade together: the first pair's alpha steps down by 1/5 an update.
    play(kKickFrame + 1, kLastMoving + 1);
    const auto held = strips(pass_->geometry(0));
    for (const auto& strip : held)
        EXPECT_LE(strip[0].color.a, 0.8f * 4.0f / 5.0f + 1e-5f);

    start(kickScene("{\"type\": \"silhouette_shell\", " + kLeg + ", \"fade_out\": 0}"));
    play(0, kKickFrame);
    EXPECT_GT(counts().strips, 0u);
    EXPECT_EQ(counts().fadingStrips, 0u);
    // A polygon on its first silhouette has one pair yet: no strip.
    EXPECT_LE(counts().strips, counts().silhouetteTriangles);
}

// Either edge rule finds a silhouette on the moving leg (Sec. 3.2.4).
TEST_F(SilhouetteShellTest, BothEdgeRulesFindASilhouette) {
    for (const char* rule : {"back", "front"}) {
        SCOPED_TRACE(rule);
        start(kickScene("{\"type\": \"silhouette_shell\", " + kLeg + ", \"edge_rule\": \"" + rule +
                        "\"}"));
        play(0, kKickFrame);
        EXPECT_GT(counts().silhouetteTriangles, 0u);
        EXPECT_GT(counts().vertices, 0u);
    }
}

TEST_F(SilhouetteShellTest, ASceneWithoutTheEffectHasNoPass) {
    scene::Scene s = kickScene("{\"type\": \"speed_lines\", " + kLeg + "}");
    Result<anim::Character> c = scene::loadCharacter(s);
    ASSERT_TRUE(c);
    EXPECT_TRUE(render::SilhouetteShellPass(ctx(), s, {&c.value(), 1}).empty());
}

// A cube whose faces have their own vertices (24, as a flat-shaded mesh has): every corner copy
// lists the 6 triangles of the 3 faces meeting there, so its averaged normal points out of the
// corner, not along one face (Sec. 3.2.2).
TEST(SilhouetteShellNormals, AveragedAcrossFlatShadedSeams) {
    std::vector<shared::SkinVertexIn> vertices;
    std::vector<uint32_t> triangles;
    flatShadedCube(vertices, triangles);
    const std::vector<uint32_t> around = render::shellVertexTriangles(vertices, triangles);
    ASSERT_EQ(around.size(), around[vertices.size()]) << "the last offset ends the lists";
    for (size_t v = 0; v < vertices.size(); ++v) {
        const uint32_t count = around[v + 1] - around[v];
        // A corner touches 3 faces: 1 or 2 triangles of each (the diagonal's ends have 2).
        EXPECT_GE(count, 3u);
        EXPECT_LE(count, 6u);
        std::set<int> faces;
        for (uint32_t k = around[v]; k < around[v + 1]; ++k)
            faces.insert(int(around[k] / 2));
        EXPECT_EQ(faces.size(), 3u) << "vertex " << v;
    }
}

TEST(SilhouetteShellUpdates, BlurTimeOverSubdivisionsApart) {
    scene::SilhouetteShellSpec s;
    s.subdivisions = 6;
    auto cadence = [&](float fps) {
        const render::ShellCadence c = render::shellCadence(s, fps);
        return std::pair{c.updatesPerFrame, c.framesPerUpdate};
    };
    EXPECT_EQ(cadence(30.0f), std::pair(1u, 1u)) << "default: one update a frame";
    s.blurTime = 0.2f;
    EXPECT_EQ(cadence(30.0f), std::pair(1u, 1u));
    s.blurTime = 0.1f;
    EXPECT_EQ(cadence(30.0f), std::pair(2u, 1u));
    s.blurTime = 1.0f;
    EXPECT_EQ(cadence(30.0f), std::pair(1u, 5u)) << "1/6 s apart: every fifth frame";
    EXPECT_EQ(cadence(60.0f), std::pair(1u, 10u));
    s.blurTime = 0.3f;
    EXPECT_EQ(cadence(30.0f), std::pair(1u, 2u)) << "1.5 frames apart rounds to 2";
    s.blurTime = 0.001f;
    EXPECT_EQ(cadence(30.0f), std::pair(uint32_t(MFX_SHELL_MAX_UPDATES_PER_FRAME), 1u));
}

// A blur time of 0.6 s over 6 subdivisions at 30 fps: one update every third frame. The frames
// between build the shell from the live mesh through the same ring; the next update's motion
// spans the three frames since the last one.
TEST_F(SilhouetteShellTest, ALongBlurTimeUpdatesEveryFewFrames) {
    start(kickScene("{\"type\": \"silhouette_shell\", " + kLeg +
                    ", \"subdivisions\": 6, \"blur_time\": 0.6}"));
    for (uint32_t f = 0; f <= kKickFrame + 2; ++f) {
        play(f, f);
        SCOPED_TRACE("frame " + std::to_string(f));
        const bool update = f > 0 && f % 3 == 0;
        EXPECT_EQ(counts().updated, update);
        if (!update) {
            EXPECT_EQ(counts().silhouetteTriangles, 0u);
        }
        if (f >= kKickFrame) {
            EXPECT_GT(counts().strips, 0u) << "the moving leg keeps its shell between updates";
            if (update) {
                EXPECT_GT(counts().silhouetteTriangles, 0u);
            }
        }
    }
}

// The scene file's options and refusals: one line naming the effect's key.
std::string sceneError(const std::string& effect) {
    Result<scene::Scene> s = scene::parseScene(R"({"effects": [)" + effect + "]}", "s.json");
    return s ? std::string() : s.error().message;
}

TEST(SilhouetteShellScene, DefaultsAndEveryOption) {
    Result<scene::Scene> d =
        scene::parseScene(R"({"effects": [{"type": "silhouette_shell"}]})", "s");
    ASSERT_TRUE(d) << d.error().message;
    EXPECT_EQ(d.value().effects[0].name, "silhouette_shell#0");
    ASSERT_TRUE(d.value().effects[0].is<scene::SilhouetteShellSpec>());
    const scene::SilhouetteShellSpec& e = *d.value().effects[0].as<scene::SilhouetteShellSpec>();
    EXPECT_EQ(e.subdivisions, 6u);
    EXPECT_FALSE(e.blurTime);
    EXPECT_EQ(e.initialAlpha, 0.8f);
    EXPECT_EQ(e.fadeOut, 3u);
    EXPECT_EQ(e.edgeRule, scene::ShellEdgeRule::Back);
    EXPECT_TRUE(e.useMeshColour);

    Result<scene::Scene> s = scene::parseScene(
        R"({"effects": [{"type": "silhouette_shell", "subdivisions": 10, "blur_time": 0.2,
        "initial_alpha": 0.5, "fade_out": 0, "edge_rule": "front", "colour": [1, 0, 0]}]})",
        "s.json");
    ASSERT_TRUE(s) << s.error().message;
    ASSERT_TRUE(s.value().effects[0].is<scene::SilhouetteShellSpec>());
    const scene::SilhouetteShellSpec& o = *s.value().effects[0].as<scene::SilhouetteShellSpec>();
    EXPECT_EQ(o.subdivisions, 10u);
    ASSERT_TRUE(o.blurTime);
    EXPECT_EQ(*o.blurTime, 0.2f);
    EXPECT_EQ(o.initialAlpha, 0.5f);
    EXPECT_EQ(o.fadeOut, 0u);
    EXPECT_EQ(o.edgeRule, scene::ShellEdgeRule::Front);
    EXPECT_FALSE(o.useMeshColour);
}

TEST(SilhouetteShellScene, RefusesBadValues) {
    EXPECT_EQ(sceneError(R"({"type": "silhouette_shell", "subdivisions": 0})"),
              "s.json: effects[0].subdivisions: 0 is outside 1..32");
    EXPECT_EQ(sceneError(R"({"type": "silhouette_shell", "initial_alpha": 1.5})"),
              "s.json: effects[0].initial_alpha: 1.5 is outside [0, 1]");
    EXPECT_EQ(sceneError(R"({"type": "silhouette_shell", "edge_rule": "side"})"),
              "s.json: effects[0].edge_rule: \"side\" is not one of: back, front");
    EXPECT_EQ(sceneError(R"({"type": "silhouette_shell", "blur_time": 0})")
                  .rfind("s.json: effects[0].blur_time: ", 0),
              0u);
}

TEST(SilhouetteShellScene, RefusesKeysOfOtherEffects) {
    EXPECT_EQ(sceneError(R"({"type": "silhouette_shell", "segments": 2})"),
              "s.json: effects[0].segments: not a key of silhouette_shell effects");
    EXPECT_EQ(sceneError(R"({"type": "silhouette_shell", "sub_samples": 2})"),
              "s.json: effects[0].sub_samples: not a key of silhouette_shell effects");
    EXPECT_EQ(sceneError(R"({"type": "swept_volume", "fade_out": 2})"),
              "s.json: effects[0].fade_out: not a key of swept_volume effects");
    EXPECT_EQ(sceneError(R"({"type": "speed_lines", "subdivisions": 2})"),
              "s.json: effects[0].subdivisions: not a key of speed_lines effects");
}

} // namespace
} // namespace mfx::test
