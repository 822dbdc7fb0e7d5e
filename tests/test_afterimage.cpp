// The afterimage toon blur (render/kinds/afterimage_pass.h; Smith 2016): geometry only while the
// bound part moves, alpha falling along each trail, a per-vertex random value that is the same in
// every run and while paused, speed thresholds that leave slow vertices alone, and the scene file's
// refusals. The scenes are small (the fighter's sword) and run a few frames.
#include "core/gpu/commands.h"
#include "core/scene/scene.h"
#include "render/frame_renderer.h"
#include "render/kinds/afterimage_pass.h"
#include "render/render_target.h"
#include "sim/scene_simulation.h"
#include "tests/effect_pass_test.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

namespace mfx::test {
namespace {

// The sword slash (0.8 s) at 30 fps, held for 6 frames after its end; `effect` is the JSON of
// one afterimage_smear effect on the sword.
scene::Scene swordScene(const std::string& effect, uint32_t frames = 30) {
    return clipScene("sword_slash", effect, frames);
}

constexpr uint32_t kSwingFrame = 11; // the blade at its fastest (0.37 s)

using AfterimageTest = EffectPassTest<render::AfterimagePass>;

uint32_t drawn(const render::AfterimagePass::Counts& c) {
    return c.triangles + c.lineVertices;
}

TEST_F(AfterimageTest, GeometryOnlyWhileTheBoundPartMoves) {
    for (const char* variant : {"smear", "speed_lines", "multi"}) {
        SCOPED_TRACE(variant);
        start(swordScene(R"({"type": "afterimage_smear", "meshes": ["sword"], "variant": ")" +
                         std::string(variant) + "\"}"));
        play(0, 0);
        EXPECT_EQ(drawn(counts()), 0u) << "the first frame has no motion yet";
        EXPECT_EQ(counts().pushedVertices, 0u);
        play(1, kSwingFrame);
        EXPECT_GT(counts().pushedVertices, 0u);
        EXPECT_GT(drawn(counts()), 0u) << "the swinging sword smears";
        play(kSwingFrame + 1, 29); // the pose is held from frame 24 on
        EXPECT_EQ(counts().fastest, 0.0f);
        EXPECT_EQ(counts().pushedVertices, 0u);
        EXPECT_EQ(drawn(counts()), 0u) << "a still sword does not";
    }
}

// The copies of a seam vertex (one bind-pose position) move together (Smith 2016, Sec. 5.4), or
// the smear tears away from the mesh: the fighter's sword, whose seam copies share a normal (they
// must draw the same random value), and the flat-shaded RiggedFigure of ../shared/assets, whose
// copies face their motion differently (every copy takes the push of the first one pushed back).
TEST_F(AfterimageTest, TheCopiesOfASeamVertexMoveTogether) {
    const std::string figure = std::string(MFX_SOURCE_DIR) + "/../shared/assets/RiggedFigure.gltf";
    struct Case {
        scene::Scene scene;
        uint32_t frame;
        bool facingDiffers;
    };
    Result<scene::Scene> flat =
        scene::parseScene(R"({"character": {"source": ")" + figure + R"(", "clip": "clip_0"},
            "output": {"width": 64, "height": 36, "fps": 30, "frames": 30},
            "effects": [{"type": "afterimage_smear", "meshes": ["Proxy"]}]})",
                          "test.json");
    ASSERT_TRUE(flat) << flat.error().message;
    for (const Case& c : {Case{swordScene(R"({"type": "afterimage_smear", "meshes": ["sword"]})"),
                               kSwingFrame, false},
                          Case{flat.value(), 10, true}}) {
        SCOPED_TRACE(c.scene.effects[0].meshes[0]);
        start(c.scene);
        play(0, c.frame);
        const render::AfterimagePass::Decisions d = pass_->decisions(0);
        ASSERT_FALSE(d.drawn.empty());
        const size_t n = d.drawn.size();
        ASSERT_GT(d.copies.size(), n);
        ASSERT_EQ(d.copies[n], d.copies.size());
        size_t seams = 0, disagreements = 0, pushed = 0;
        for (size_t v = 0; v < n; ++v) {
            const uint32_t first = d.copies[v], end = d.copies[v + 1];
            ASSERT_LT(first, end);
            if (end - first > 1) ++seams;
            // The first copy the smear pushed back on its own, if any.
            const shared::TrajectoryVertex* leader = nullptr;
            bool anyStill = false;
            for (uint32_t k = first; k < end; ++k) {
                const shared::TrajectoryVertex& copy = d.decided[d.copies[k]];
                if (copy.position.w == 0.0f)
                    anyStill = true;
                else if (!leader)
                    leader = &copy;
            }
            if (leader && anyStill) ++disagreements;
            const shared::TrajectoryVertex& drawn = d.drawn[v];
            ASSERT_EQ(drawn.position.w, leader ? 1.0f : 0.0f) << "vertex " << v;
            if (!leader) continue;
            ++pushed;
            EXPECT_EQ(glm::vec3(drawn.velocity), glm::vec3(leader->velocity)) << "vertex " << v;
            for (uint32_t k = first; k < end; ++k) {
                const glm::vec3 other = glm::vec3(d.drawn[d.copies[k]].position);
                EXPECT_LE(glm::length(glm::vec3(drawn.position) - other), 1e-5f)
                    << "vertex " << v << " and its copy " << d.copies[k] << " drawn apart";
            }
        }
        EXPECT_GT(seams, 0u) << "the mesh has seam vertices";
        EXPECT_GT(pushed, 0u);
        if (c.facingDiffers) {
            EXPECT_GT(disagreements, 0u) << "flat-shaded copies face their motion differently";
        } else {
            EXPECT_EQ(disagreements, 0u);
        }
        EXPECT_EQ(counts().pushedVertices, pushed);
    }
}

TEST_F(AfterimageTest, NothingOutsideTheEffectsWindow) {
    start(swordScene(R"({"type": "afterimage_smear", "meshes": ["sword"], "start": 0.6})"));
    play(0, kSwingFrame);
    EXPECT_EQ(drawn(counts()), 0u);
    EXPECT_GT(counts().fastest, 0.0f) << "the history is recorded all the same";
}

// Alpha at the live mesh is alpha_start and falls to alpha_end at the far end, monotone in the
// vertex's place along the trail (position.w: 0 at the mesh, 1 at the end).
void expectAlphaFallsAlongTrails(const std::vector<shared::TrajectoryVertex>& vertices) {
    ASSERT_FALSE(vertices.empty());
    std::vector<std::pair<float, float>> byPlace; // (place, alpha)
    for (const shared::TrajectoryVertex& v : vertices)
        byPlace.emplace_back(v.position.w, v.color.a);
    std::sort(byPlace.begin(), byPlace.end());
    for (size_t k = 1; k < byPlace.size(); ++k)
        ASSERT_LE(byPlace[k].second, byPlace[k - 1].second + 1e-6f)
            << "at place " << byPlace[k].first;
    EXPECT_FLOAT_EQ(byPlace.front().second, 0.9f);
    EXPECT_FLOAT_EQ(byPlace.back().second, 0.1f);
}

TEST_F(AfterimageTest, AlphaFallsAlongEachSpeedLine) {
    start(swordScene(R"({"type": "afterimage_smear", "meshes": ["sword"],
        "variant": "speed_lines", "colour": [1, 1, 1, 1], "alpha_start": 0.9, "alpha_end": 0.1})"));
    play(0, kSwingFrame);
    const auto lines = pass_->geometry(0);
    ASSERT_EQ(lines.size() % 2, 0u);
    for (size_t k = 0; k < lines.size(); k += 2) {
        EXPECT_EQ(lines[k].position.w, 0.0f);
        EXPECT_EQ(lines[k + 1].position.w, 1.0f);
        EXPECT_GT(lines[k].color.a, lines[k + 1].color.a);
    }
    expectAlphaFallsAlongTrails(lines);
}

TEST_F(AfterimageTest, AlphaFallsAlongEachArc) {
    start(swordScene(R"({"type": "afterimage_smear", "meshes": ["sword"], "variant": "multi",
        "afterimages": 4, "colour": [1, 1, 1, 1], "alpha_start": 0.9, "alpha_end": 0.1,
        "alpha_power": 2})"));
    play(0, kSwingFrame);
    const auto arcs = pass_->geometry(0);
    ASSERT_EQ(arcs.size() % 24, 0u) << "4 quads of 2 triangles per edge";
    for (size_t edge = 0; edge < arcs.size(); edge += 24)
        expectAlphaFallsAlongTrails(
            {arcs.begin() + ptrdiff_t(edge), arcs.begin() + ptrdiff_t(edge + 24)});
}

bool sameGeometry(const std::vector<shared::TrajectoryVertex>& a,
                  const std::vector<shared::TrajectoryVertex>& b) {
    if (a.size() != b.size()) return false;
    for (size_t k = 0; k < a.size(); ++k)
        if (a[k].position != b[k].position || a[k].color != b[k].color) return false;
    return true;
}

// Sorted, so that the order atomics appended in does not matter.
std::vector<shared::TrajectoryVertex> sortedLines(std::vector<shared::TrajectoryVertex> lines) {
    std::vector<std::pair<shared::TrajectoryVertex, shared::TrajectoryVertex>> pairs;
    for (size_t k = 0; k + 1 < lines.size(); k += 2)
        pairs.emplace_back(lines[k], lines[k + 1]);
    // By both ends: vertices at one place (a seam) start several lines, which the GPU's
    // invocations append in any order.
    std::sort(pairs.begin(), pairs.end(), [](const auto& x, const auto& y) {
        const glm::vec4 &a = x.first.position, &b = y.first.position;
        const glm::vec4 &c = x.second.position, &d = y.second.position;
        return std::tie(a.x, a.y, a.z, c.x, c.y, c.z) < std::tie(b.x, b.y, b.z, d.x, d.y, d.z);
    });
    std::vector<shared::TrajectoryVertex> out;
    for (const auto& [a, b] : pairs) {
        out.push_back(a);
        out.push_back(b);
    }
    return out;
}

TEST_F(AfterimageTest, RandomnessIsTheSameInEveryRun) {
    const scene::Scene s = swordScene(R"({"type": "afterimage_smear", "meshes": ["sword"],
        "variant": "speed_lines", "random_min": 0.2, "random_max": 1.0})");
    start(s);
    play(0, kSwingFrame);
    const auto first = sortedLines(pass_->geometry(0));
    ASSERT_FALSE(first.empty());
    start(s);
    play(0, kSwingFrame);
    EXPECT_TRUE(sameGeometry(first, sortedLines(pass_->geometry(0))));
}

// A paused view redraws its frame with FrameRenderer::recordDraw: the smear and the picture stay
// exactly as they were (the ring advances with scene frames only, and R is a hash of the vertex).
TEST_F(AfterimageTest, APausedFrameDoesNotChange) {
    const scene::Scene s = swordScene(R"({"type": "afterimage_smear", "meshes": ["sword"],
        "strength_animation": 3, "random_min": 0.3, "taper": 0.5})");
    Result<anim::Character> c = scene::loadCharacter(s);
    ASSERT_TRUE(c);
    auto sim = sim::SceneSimulation::create(ctx(), s, c.value());
    ASSERT_TRUE(sim);
    render::FrameRenderer renderer(ctx(), *sim.value(), 64, 36, VK_SAMPLE_COUNT_1_BIT);
    for (uint32_t f = 0; f <= kSwingFrame; ++f) {
        gpu::submitOneShot(ctx(),
                           [&](VkCommandBuffer cmd) { renderer.record(cmd, *sim.value(), f); });
        sim.value()->finishFrame();
    }
    const render::AfterimagePass* pass = renderer.effectPass<render::AfterimagePass>();
    ASSERT_NE(pass, nullptr);
    const auto smear = pass->geometry(0);
    ASSERT_GT(pass->counts(0).triangles, 0u);
    const std::vector<uint8_t> picture = render::readColor(ctx(), renderer.output());
    for (int redraw = 0; redraw < 3; ++redraw) {
        gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
            renderer.recordDraw(cmd, *sim.value(), sim.value()->frameTime(kSwingFrame));
        });
        EXPECT_TRUE(sameGeometry(smear, pass->geometry(0)));
        EXPECT_EQ(picture, render::readColor(ctx(), renderer.output()));
    }
}

// With R = 1 and both strengths 1 a speed line is the vertex's motion this frame, reversed, so
// its length is the vertex's speed (per frame).
TEST_F(AfterimageTest, SpeedThresholdsExcludeSlowVertices) {
    const std::string common = R"("type": "afterimage_smear", "meshes": ["sword"],
        "variant": "speed_lines", "random_min": 1, "random_max": 1, "strength_character": 1,
        "strength_animation": 1)";
    start(swordScene("{" + common + "}"));
    play(0, kSwingFrame);
    const uint32_t all = counts().lineVertices;
    const float fastest = counts().fastest;
    ASSERT_GT(all, 0u);

    start(swordScene("{" + common + R"(, "relative_speed": 0.65})"));
    play(0, kSwingFrame);
    const auto relative = pass_->geometry(0);
    ASSERT_GT(relative.size(), 0u);
    EXPECT_LT(relative.size(), all) << "the hilt moves slower than the blade's tip";
    for (size_t k = 0; k < relative.size(); k += 2)
        EXPECT_GE(glm::length(glm::vec3(relative[k + 1].position - relative[k].position)),
                  0.65f * fastest * 0.999f);

    const float minSpeed = 0.8f * fastest * 30.0f; // world units per second
    start(swordScene("{" + common + R"(, "min_speed": )" + std::to_string(minSpeed) + "}"));
    play(0, kSwingFrame);
    const auto absolute = pass_->geometry(0);
    ASSERT_GT(absolute.size(), 0u);
    EXPECT_LT(absolute.size(), all);
    for (size_t k = 0; k < absolute.size(); k += 2)
        EXPECT_GE(glm::length(glm::vec3(absolute[k + 1].position - absolute[k].position)),
                  minSpeed / 30.0f * 0.999f);
}

TEST_F(AfterimageTest, ASceneWithoutTheEffectHasNoPass) {
    scene::Scene s = swordScene(R"({"type": "speed_lines", "meshes": ["sword"]})");
    Result<anim::Character> c = scene::loadCharacter(s);
    ASSERT_TRUE(c);
    EXPECT_TRUE(render::AfterimagePass(ctx(), s, {&c.value(), 1}).empty());
}

// The scene file's refusals: one line naming the effect's key.
std::string sceneError(const std::string& effect) {
    Result<scene::Scene> s = scene::parseScene(R"({"effects": [)" + effect + "]}", "s.json");
    return s ? std::string() : s.error().message;
}

TEST(AfterimageScene, ReadsEveryOption) {
    Result<scene::Scene> s = scene::parseScene(
        R"({"effects": [{"type": "afterimage_smear", "variant": "multi", "strength_character": 0.5,
        "strength_animation": 4, "random_min": 0.25, "random_max": 0.75, "random_threshold": 0.5,
        "taper": 2, "min_speed": 1.5, "relative_speed": 0.65, "afterimages": 7,
        "influence_power": 3}]})",
        "s.json");
    ASSERT_TRUE(s) << s.error().message;
    ASSERT_TRUE(s.value().effects[0].is<scene::AfterimageSpec>());
    const scene::AfterimageSpec& a = *s.value().effects[0].as<scene::AfterimageSpec>();
    EXPECT_EQ(s.value().effects[0].name, "afterimage_smear#0");
    EXPECT_EQ(a.variant, scene::AfterimageVariant::Multi);
    EXPECT_EQ(a.strengthCharacter, 0.5f);
    EXPECT_EQ(a.strengthAnimation, 4.0f);
    EXPECT_EQ(a.randomMin, 0.25f);
    EXPECT_EQ(a.randomMax, 0.75f);
    EXPECT_EQ(a.randomThreshold, 0.5f);
    EXPECT_EQ(a.taper, 2.0f);
    EXPECT_EQ(a.minSpeed, 1.5f);
    EXPECT_EQ(a.relativeSpeed, 0.65f);
    EXPECT_EQ(a.afterimages, 7u);
    EXPECT_EQ(a.influencePower, 3.0f);
}

TEST(AfterimageScene, RefusesBadValues) {
    EXPECT_EQ(sceneError(R"({"type": "afterimage_smear", "strength_animation": -1})"),
              "s.json: effects[0].strength_animation: -1 is outside [0, 1000]");
    EXPECT_EQ(sceneError(R"({"type": "afterimage_smear", "random_min": 0.8, "random_max": 0.2})"),
              "s.json: effects[0].random_min: 0.8 is more than random_max (0.2)");
    EXPECT_EQ(sceneError(R"({"type": "afterimage_smear", "relative_speed": 2})"),
              "s.json: effects[0].relative_speed: 2 is outside [0, 1]");
    EXPECT_EQ(sceneError(R"({"type": "afterimage_smear", "variant": "wobble"})"),
              "s.json: effects[0].variant: \"wobble\" is not one of: smear, speed_lines, multi");
    EXPECT_EQ(sceneError(R"({"type": "afterimage_smear", "taper": "steep"})"),
              "s.json: effects[0].taper: expected a number, got a string");
    EXPECT_NE(sceneError(R"({"type": "afterimage_smear", "taper": 1e999})").find("not valid JSON"),
              std::string::npos);
}

TEST(AfterimageScene, RefusesKeysOfOtherEffectsAndVariants) {
    EXPECT_EQ(sceneError(R"({"type": "afterimage_smear", "strenght_animation": 1})")
                  .rfind("s.json: effects[0].strenght_animation: unknown key; keys here are: ", 0),
              0u);
    EXPECT_EQ(sceneError(R"({"type": "afterimage_smear", "lifetime": 4})"),
              "s.json: effects[0].lifetime: not a key of afterimage_smear effects");
    EXPECT_EQ(sceneError(R"({"type": "speed_lines", "taper": 1})"),
              "s.json: effects[0].taper: not a key of speed_lines effects");
    EXPECT_EQ(sceneError(R"({"type": "afterimage_smear", "afterimages": 3})"),
              "s.json: effects[0].afterimages: only for \"variant\": \"multi\" (the variant is "
              "\"smear\")");
    EXPECT_EQ(sceneError(R"({"type": "afterimage_smear", "variant": "multi", "width": 0.1})"),
              "s.json: effects[0].width: only for \"variant\": \"speed_lines\" (the variant is "
              "\"multi\")");
    EXPECT_EQ(sceneError(R"({"type": "afterimage_smear", "shape": "tube"})"),
              "s.json: effects[0].shape: only for \"variant\": \"speed_lines\" (the variant is "
              "\"smear\")");
}

} // namespace
} // namespace mfx::test
