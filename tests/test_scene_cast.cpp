// Scenes of several characters: "characters" (names, the single "character" still read as one),
// effects naming the character they follow, the refusals, a clip's delay, the framing fitted to
// every character, and the simulation and the frame drawing each effect on its own character.
#include "core/anim/fighter.h"
#include "core/gpu/commands.h"
#include "core/scene/scene.h"
#include "core/scene/scene_fit.h"
#include "gpu_test.h"
#include "render/render_target.h"
#include "scene_render_util.h"
#include "shaders/shared/trajectory.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace mfx::test {
namespace {

// Two fighters 3 m apart facing each other across x: "red" at x = -1.5 (facing +x) kicking,
// "blue" at x = +1.5 (facing -x) spinning; speed-lines on each one's right foot.
const char* const kVersus = R"({
  "characters": [
    {"name": "red", "clip": "roundhouse_kick", "position": [-1.5, 0, 0], "yaw_degrees": 90},
    {"name": "blue", "clip": "spin", "position": [1.5, 0, 0], "yaw_degrees": -90}
  ],
  "output": {"width": 320, "height": 180},
  "effects": [
    {"type": "speed_lines", "name": "red kick", "bones": ["foot_r", "toe_r"], "stride": 8},
    {"type": "speed_lines", "name": "blue spin", "character": "blue",
     "bones": ["foot_r", "toe_r"], "stride": 8}
  ]
})";

scene::Scene parse(const std::string& text) {
    Result<scene::Scene> s = scene::parseScene(text, "cast.json");
    EXPECT_TRUE(s.ok()) << s.error().message;
    return s ? std::move(s).value() : scene::Scene{};
}

std::string refusal(const std::string& text) {
    Result<scene::Scene> s = scene::parseScene(text, "cast.json");
    return s ? std::string("(accepted)") : s.error().message;
}

TEST(SceneCast, CharactersAreReadWithTheirNamesAndEffectsFollowTheOneTheyName) {
    const scene::Scene s = parse(kVersus);
    ASSERT_EQ(s.characters.size(), 2u);
    EXPECT_EQ(s.characters[0].name, "red");
    EXPECT_EQ(s.characters[1].name, "blue");
    EXPECT_EQ(s.characters[1].clip, "spin");
    EXPECT_FLOAT_EQ(s.characters[1].yawDegrees, -90.0f);
    EXPECT_EQ(scene::effectCharacter(s, s.effects[0]), 0u); // no "character": the first
    EXPECT_EQ(scene::effectCharacter(s, s.effects[1]), 1u);
}

TEST(SceneCast, TheSingleCharacterIsACastOfOneNamedP1AndUnnamedOnesAreNumbered) {
    const scene::Scene one =
        parse(R"({"character": {"clip": "spin"}, "effects": [{"type": "speed_lines"}]})");
    ASSERT_EQ(one.characters.size(), 1u);
    EXPECT_EQ(one.characters[0].name, "p1");
    EXPECT_EQ(one.characters[0].clip, "spin");
    const scene::Scene two = parse(R"({"characters": [{}, {"clip": "idle"}],
        "effects": [{"type": "speed_lines", "character": "p2"}]})");
    ASSERT_EQ(two.characters.size(), 2u);
    EXPECT_EQ(two.characters[1].name, "p2");
    EXPECT_EQ(scene::effectCharacter(two, two.effects[0]), 1u);
}

TEST(SceneCast, MalformedCastsAreRefusedNamingTheKey) {
    const std::string effects = R"("effects": [{"type": "speed_lines"}])";
    EXPECT_EQ(refusal(R"({"character": {}, "characters": [{}], )" + effects + "}"),
              "cast.json: characters: give \"character\" (one) or \"characters\" (a list), not "
              "both");
    EXPECT_EQ(refusal(R"({"characters": [], )" + effects + "}"),
              "cast.json: characters: 0 characters; 1 to 4");
    EXPECT_EQ(refusal(R"({"characters": [{}, {}, {}, {}, {}], )" + effects + "}"),
              "cast.json: characters: 5 characters; 1 to 4");
    EXPECT_EQ(refusal(R"({"characters": {"name": "a"}, )" + effects + "}"),
              "cast.json: characters: expected an array of characters, got an object");
    EXPECT_EQ(refusal(R"({"characters": [{"name": "a"}, {"name": "a"}], )" + effects + "}"),
              "cast.json: characters[1].name: \"a\" is the name of characters[0]; give each a "
              "name of its own");
    EXPECT_EQ(refusal(R"({"characters": [{"name": ""}], )" + effects + "}"),
              "cast.json: characters[0].name: must not be empty");
    EXPECT_EQ(refusal(R"({"characters": [{"name": "a"}, {"name": "b"}],
        "effects": [{"type": "smoke", "character": "c"}]})"),
              "cast.json: effects[0].character: no character \"c\"; characters are: a, b");
    EXPECT_EQ(refusal(R"({"characters": [{"delay": -1}], )" + effects + "}"),
              "cast.json: characters[0].delay: -1 is outside [0, 10000]");
}

TEST(SceneCast, ACharactersBonesAreCheckedOnItsOwnRig) {
    scene::Scene s = parse(R"({"characters": [{"name": "a"}, {"name": "b"}],
        "effects": [{"type": "speed_lines", "character": "b", "bones": ["no_such_bone"]}]})");
    const anim::Character fighter = anim::makeFighter();
    const scene::Cast cast = {fighter, fighter};
    EXPECT_TRUE(scene::checkNames(s, 0, fighter).ok()); // a has no effect
    const Status b = scene::checkNames(s, 1, fighter);
    ASSERT_FALSE(b.ok());
    EXPECT_NE(b.error().message.find("cast.json: effects[0].bones[0]: "), std::string::npos)
        << b.error().message;
    EXPECT_FALSE(scene::checkNames(s, cast).ok());
    s.characters[0].clip = "no_such_clip";
    const Status clip = scene::checkNames(s, 0, fighter);
    ASSERT_FALSE(clip.ok());
    EXPECT_NE(clip.error().message.find("cast.json: characters[0].clip: no clip \"no_such_clip\""),
              std::string::npos)
        << clip.error().message;
}

TEST(SceneCast, ADelayHoldsTheFirstPoseThenPlaysAndTheSceneLastsForTheLongestCharacter) {
    scene::Scene s = parse(R"({"characters": [{"clip": "roundhouse_kick"},
        {"clip": "hit_react", "delay": 0.4, "speed": 2}], "effects": [{"type": "speed_lines"}]})");
    const anim::Character fighter = anim::makeFighter();
    const scene::CharacterSpec& late = s.characters[1];
    EXPECT_FLOAT_EQ(scene::clipTimeAt(late, fighter, 0.0f), 0.0f);
    EXPECT_FLOAT_EQ(scene::clipTimeAt(late, fighter, 0.4f), 0.0f);
    EXPECT_NEAR(scene::clipTimeAt(late, fighter, 0.5f), 0.2f, 1e-6f);
    // hit_react is 0.75 s: at speed 2 it ends 0.375 s after its delay, 0.775 s into the scene;
    // the kick (0.9 s) lasts longer and sets the frame count.
    EXPECT_NEAR(scene::characterDuration(late, fighter), 0.775f, 1e-6f);
    const scene::Cast cast = {fighter, fighter};
    EXPECT_FLOAT_EQ(scene::sceneDuration(s, cast), 0.9f);
    EXPECT_EQ(scene::frameCount(s, cast), 27u);
    s.characters[1].delay = 1.0f;
    EXPECT_EQ(scene::frameCount(s, cast), 42u); // 1 + 0.375 s at 30 fps, rounded up
}

// The framing of a cast: every character's animated bounds inside the view, the stage under the
// lowest of them, and the camera looking from the side of the line between two fighters that face
// each other (not from behind either).
TEST(SceneCast, TheFramingFitsEveryCharacter) {
    scene::Scene s = parse(kVersus);
    const anim::Character fighter = anim::makeFighter();
    const scene::Cast cast = {fighter, fighter};
    ASSERT_TRUE(scene::fitScene(s, cast).ok());
    const scene::CameraSpec& camera = s.camera;
    const glm::vec3 toCamera = glm::normalize(camera.position - camera.target);
    EXPECT_GT(toCamera.z, 0.5f) << "the camera looks at the fighters from the side";
    const float aspect = float(s.output.width) / float(s.output.height);
    const glm::mat4 viewProjection =
        glm::perspective(glm::radians(camera.fovDegrees), aspect, camera.nearPlane,
                         camera.farPlane) *
        glm::lookAt(camera.position, camera.target, glm::vec3(0, 1, 0));
    float lowest = 1e9f;
    for (size_t c = 0; c < cast.size(); ++c) {
        scene::Scene alone = s;
        alone.characters = {s.characters[c]};
        const scene::Bounds b = scene::animatedBounds(alone, cast[c]);
        ASSERT_FALSE(b.empty());
        lowest = std::min(lowest, b.low.y);
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec4 p = viewProjection * glm::vec4((corner & 1) ? b.high.x : b.low.x,
                                                           (corner & 2) ? b.high.y : b.low.y,
                                                           (corner & 4) ? b.high.z : b.low.z, 1.0f);
            EXPECT_LE(std::abs(p.x / p.w), 1.0f) << s.characters[c].name << " corner " << corner;
            EXPECT_LE(std::abs(p.y / p.w), 1.0f) << s.characters[c].name << " corner " << corner;
        }
    }
    EXPECT_NEAR(s.stage.floorHeight, lowest, 1e-5f);
    ASSERT_TRUE(s.stage.shadowCentre.has_value());
    EXPECT_NEAR(s.stage.shadowCentre->x, 0.0f, 0.5f); // between the two
}

// The newest segment's positions of a trajectory effect, read back.
std::vector<glm::vec3> newestPositions(const gpu::Context& ctx,
                                       const sim::SceneSimulation::TrajectoryEffect& effect) {
    const auto vertices =
        gpu::readBufferAs<shared::TrajectoryVertex>(ctx, effect.queue->vertices());
    const trajectory::LiveSegment newest = effect.queue->newestSegment();
    std::vector<glm::vec3> out;
    for (uint32_t v = 0; v < effect.queue->verticesPerSegment(); ++v)
        out.push_back(glm::vec3(vertices[newest.firstVertex + v].position));
    return out;
}

using SceneCastGpu = GpuTest;

// Each effect's segment is built on its own character: red's kick lines at red's place (x < 0),
// blue's spin lines at blue's (x > 0), each within a leg's reach of where its character stands.
TEST_F(SceneCastGpu, EachEffectsSegmentsAreBuiltOnTheCharacterItFollows) {
    const scene::Scene s = parse(kVersus);
    const anim::Character fighter = anim::makeFighter();
    const scene::Cast cast = {fighter, fighter};
    auto created = sim::SceneSimulation::create(ctx(), s, cast);
    ASSERT_TRUE(created) << created.error().message;
    sim::SceneSimulation& simulation = *created.value();
    for (uint32_t f = 0; f <= 12; ++f)
        simulation.runFrame(f);
    ASSERT_EQ(simulation.trajectories().size(), 2u);
    for (size_t e = 0; e < 2; ++e) {
        const auto& effect = simulation.trajectories()[e];
        EXPECT_EQ(effect.character, e);
        const glm::vec3 at = s.characters[e].position;
        const std::vector<glm::vec3> positions = newestPositions(ctx(), effect);
        ASSERT_FALSE(positions.empty());
        for (const glm::vec3& p : positions) {
            EXPECT_LT(glm::length(glm::vec2(p.x - at.x, p.z - at.z)), 1.3f)
                << s.effects[e].name << " at (" << p.x << ", " << p.z << ")";
            EXPECT_EQ(p.x > 0.0f, e == 1) << s.effects[e].name;
        }
    }
    // The simulation's poses: each character in its own clip.
    EXPECT_NE(simulation.framePose(0).world[size_t(*fighter.findNode("foot_r"))],
              simulation.framePose(1).world[size_t(*fighter.findNode("foot_r"))]);
}

// The frame draws both fighters: with blue removed, the part of the picture where blue stands
// (the right third) loses the pixels blue covered; with both, each third has a character.
TEST_F(SceneCastGpu, TheFrameDrawsEveryCharacter) {
    scene::Scene both = parse(kVersus);
    both.effects.clear();
    both.stage.backdrop = false;
    both.stage.floor = false;
    scene::Scene redOnly = both;
    redOnly.characters.pop_back();
    // The same camera for both pictures: the framing of the two.
    const anim::Character fighter = anim::makeFighter();
    ASSERT_TRUE(scene::fitScene(both, scene::Cast{fighter, fighter}).ok());
    redOnly.camera = both.camera;
    redOnly.stage = both.stage;
    auto covered = [&](const scene::Scene& s, uint32_t x0, uint32_t x1) {
        Result<DrawnScene> drawn = drawScene(ctx(), s, 320, 180, VK_SAMPLE_COUNT_1_BIT);
        EXPECT_TRUE(drawn) << drawn.error().message;
        if (!drawn) return size_t(0);
        drawn.value().playTo(ctx(), 6);
        const std::vector<uint8_t> pixels =
            render::readColor(ctx(), drawn.value().renderer->output());
        // Without stage, whatever differs from the top-left corner's clear colour is a character.
        const uint8_t* clear = &pixels[0];
        size_t n = 0;
        for (uint32_t y = 0; y < 180; ++y)
            for (uint32_t x = x0; x < x1; ++x) {
                const uint8_t* p = &pixels[(size_t(y) * 320 + x) * 4];
                if (std::abs(int(p[0]) - clear[0]) + std::abs(int(p[1]) - clear[1]) +
                        std::abs(int(p[2]) - clear[2]) >
                    30)
                    ++n;
            }
        return n;
    };
    const size_t bothLeft = covered(both, 0, 140), bothRight = covered(both, 180, 320);
    const size_t redLeft = covered(redOnly, 0, 140), redRight = covered(redOnly, 180, 320);
    RecordProperty("pixels", std::to_string(bothLeft) + " " + std::to_string(bothRight) + " " +
                                 std::to_string(redLeft) + " " + std::to_string(redRight));
    EXPECT_GT(bothLeft, 150u);
    EXPECT_GT(bothRight, 150u);
    EXPECT_GT(redLeft, 150u);
    EXPECT_LT(redRight, bothRight / 10);
}

} // namespace
} // namespace mfx::test
