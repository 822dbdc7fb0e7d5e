// Scene files: defaults, the smallest complete scene, the README's example, and a table of
// malformed scenes each refused with one line naming the key path.
#include "core/scene/scene.h"

#include "core/anim/fighter.h"
#include "core/scene/kinds/smoke_effect.h"
#include "core/scene/kinds/trail_effects.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

namespace mfx::test {
namespace {

scene::Scene parse(const std::string& text) {
    Result<scene::Scene> s = scene::parseScene(text, "test.json");
    EXPECT_TRUE(s.ok()) << s.error().message;
    return s ? std::move(s).value() : scene::Scene{};
}

TEST(SceneFile, SpeedLinesAloneIsACompleteScene) {
    const scene::Scene s = parse(R"({"effects": [{"type": "speed_lines"}]})");
    ASSERT_EQ(s.effects.size(), 1u);
    EXPECT_TRUE(s.effects[0].is<scene::SpeedLinesSpec>());
    EXPECT_STREQ(s.effects[0].type(), "speed_lines");
    EXPECT_TRUE(s.effects[0].bones.empty());
    EXPECT_TRUE(s.effects[0].automaticBones); // fitScene binds it to the fastest limb
    EXPECT_TRUE(s.effects[0].meshes.empty());
    EXPECT_EQ(s.effects[0].name, "speed_lines#0");
    EXPECT_EQ(s.characters[0].source, "fighter");
    EXPECT_EQ(s.output.width, 1280u);
    const anim::Character fighter = anim::makeFighter();
    EXPECT_TRUE(scene::checkNames(s, fighter).ok());
    EXPECT_EQ(scene::sceneClip(s.characters[0], fighter).name, "roundhouse_kick");
    EXPECT_EQ(scene::frameCount(s, fighter), 27u); // 0.9 s at 30 fps
}

TEST(SceneFile, EveryKeyIsRead) {
    const scene::Scene s = parse(R"({
        "character": {"source": "fighter", "clip": "sword_slash", "start": 0.1, "end": 0.7,
                      "speed": 0.5, "loop": true, "position": [1, 0, -1], "yaw_degrees": 90},
        "camera": {"position": [0, 2, 5], "target": [0, 1, 0], "fov_degrees": 35, "near": 0.1,
                   "far": 20},
        "lights": [{"direction": [0, -1, 0], "colour": [1, 0.5, 0.5], "intensity": 2,
                    "shadow": false}],
        "stage": {"floor": false, "backdrop": true, "floor_colour": [0.1, 0.2, 0.3],
                  "backdrop_colour": [0.3, 0.2, 0.1]},
        "output": {"width": 320, "height": 180, "fps": 60, "frames": 12},
        "post": {"exposure": -1.5, "bloom": 0.2, "tone_map": "aces"},
        "effects": [
            {"type": "smoke", "name": "puff", "bones": ["foot_r"], "meshes": ["body"],
             "min_bone_weight": 0.3, "start": 0.2, "end": 0.9, "sub_samples": 3, "lifetime": 4,
             "stride": 2, "colour": [0.2, 0.4, 0.6, 0.8], "alpha_start": 0.9, "alpha_end": 0.1,
             "alpha_power": 2, "grid": [32, 24, 16], "cell_size": 0.04, "jacobi": 30,
             "fade": 1.5, "drag": 2, "buoyancy": 0.5, "vorticity": 2, "impulse_k": 0.7, "radius": 0.1,
             "strength": 3, "emission": "surface", "surface_step": 0.01, "max_emitters": 100,
             "sleep_threshold": 0.001, "look": "fire", "glow": 2, "cel_bands": 3},
            {"type": "speed_lines", "width": 0.02},
            {"type": "motion_particles", "size": 0.03},
            {"type": "motion_blur"}
        ]})");
    EXPECT_EQ(s.characters[0].clip, "sword_slash");
    EXPECT_FLOAT_EQ(*s.characters[0].end, 0.7f);
    EXPECT_TRUE(s.characters[0].loop);
    EXPECT_FLOAT_EQ(s.camera.fovDegrees, 35.0f);
    EXPECT_FALSE(s.lights[0].shadow);
    EXPECT_FALSE(s.stage.floor);
    EXPECT_EQ(*s.output.frames, 12u);
    EXPECT_FLOAT_EQ(s.post.exposure, -1.5f);
    EXPECT_FLOAT_EQ(s.post.bloom, 0.2f);
    EXPECT_EQ(s.post.toneMap, scene::ToneMap::Aces);
    EXPECT_EQ(s.effects[0].name, "puff");
    const auto* smoke = s.effects[0].as<scene::SmokeSpec>();
    const auto* lines = s.effects[1].as<scene::SpeedLinesSpec>();
    const auto* particles = s.effects[2].as<scene::MotionParticlesSpec>();
    const auto* blur = s.effects[3].as<scene::MotionBlurSpec>();
    ASSERT_TRUE(smoke && lines && particles && blur);
    EXPECT_EQ(smoke->grid.cells, (std::array<uint32_t, 3>{32, 24, 16}));
    EXPECT_EQ(smoke->emission, scene::Emission::Surface);
    EXPECT_EQ(smoke->maxEmitters, 100u);
    EXPECT_EQ(smoke->shading.preset, scene::SmokePreset::Fire);
    EXPECT_FLOAT_EQ(smoke->shading.glow, 2.0f);
    EXPECT_EQ(smoke->shading.celBands, 3u);
    EXPECT_FLOAT_EQ(smoke->grid.drag, 2.0f);
    EXPECT_FLOAT_EQ(smoke->trail.colour.a, 0.8f);
    EXPECT_FLOAT_EQ(lines->width, 0.02f);
    EXPECT_FLOAT_EQ(particles->size, 0.03f);
    EXPECT_TRUE(blur->trail.useMeshColour);
    const anim::Character fighter = anim::makeFighter();
    EXPECT_TRUE(scene::checkNames(s, fighter).ok());
    // Half speed over 0.6 s of clip: 1.2 s of scene; the clip time loops.
    EXPECT_FLOAT_EQ(scene::sceneDuration(s, fighter), 1.2f);
    EXPECT_NEAR(scene::clipTimeAt(s.characters[0], fighter, 0.4f), 0.3f, 1e-6f);
    EXPECT_NEAR(scene::clipTimeAt(s.characters[0], fighter, 1.4f), 0.2f, 1e-5f);
}

// "domain": "sparse": a virtual domain of 256^3 cells unless "grid" says otherwise (rounded up to
// whole bricks), a budget of 4096 bricks unless "max_bricks" does; a dense grid is as it was.
TEST(SceneFile, SmokeAsksForTheSparseDomain) {
    const scene::Scene s = parse(R"({"effects": [
        {"type": "smoke", "name": "a", "domain": "sparse"},
        {"type": "smoke", "name": "b", "domain": "sparse", "grid": [512, 121, 256],
         "max_bricks": 900, "live_speed": 0.5, "origin": [-3, 0, -6.5]},
        {"type": "smoke", "name": "c"}]})");
    ASSERT_EQ(s.effects.size(), 3u);
    const scene::SmokeGridSpec& a = s.effects[0].as<scene::SmokeSpec>()->grid;
    const scene::SmokeGridSpec& b = s.effects[1].as<scene::SmokeSpec>()->grid;
    const scene::SmokeGridSpec& c = s.effects[2].as<scene::SmokeSpec>()->grid;
    EXPECT_TRUE(a.sparse());
    EXPECT_EQ(a.cells, (std::array<uint32_t, 3>{256, 256, 256}));
    EXPECT_EQ(a.maxBricks, 4096u);
    EXPECT_FLOAT_EQ(a.cellSize, 0.05f);
    EXPECT_EQ(b.cells, (std::array<uint32_t, 3>{512, 128, 256})); // in whole bricks
    EXPECT_EQ(b.maxBricks, 900u);
    EXPECT_FLOAT_EQ(a.liveSpeed, 0.1f);
    EXPECT_FLOAT_EQ(b.liveSpeed, 0.5f);
    EXPECT_FALSE(a.origin.has_value());
    ASSERT_TRUE(b.origin.has_value());
    EXPECT_EQ(*b.origin, glm::vec3(-3.0f, 0.0f, -6.5f));
    EXPECT_FALSE(c.sparse());
    EXPECT_EQ(c.cells, (std::array<uint32_t, 3>{48, 48, 48}));
    EXPECT_FALSE(a == c); // a sparse and a dense effect never share a grid
}

// Smoke collides with the character unless "collide": false, on either domain.
TEST(SceneFile, SmokeCollidesByDefault) {
    const scene::Scene s = parse(R"({"effects": [
        {"type": "smoke", "name": "a"},
        {"type": "smoke", "name": "b", "collide": false},
        {"type": "smoke", "name": "c", "pressure": "mgpcg"},
        {"type": "smoke", "name": "d", "domain": "sparse"},
        {"type": "smoke", "name": "e", "domain": "sparse", "collide": false,
         "collide_bones": ["foot_r"], "collide_thickness": 0.1}]})");
    ASSERT_EQ(s.effects.size(), 5u);
    EXPECT_TRUE(s.effects[0].as<scene::SmokeSpec>()->grid.collide);
    EXPECT_FALSE(s.effects[1].as<scene::SmokeSpec>()->grid.collide);
    EXPECT_TRUE(s.effects[2].as<scene::SmokeSpec>()->grid.collide);
    EXPECT_TRUE(s.effects[3].as<scene::SmokeSpec>()->grid.collide);
    const scene::SmokeGridSpec& e = s.effects[4].as<scene::SmokeSpec>()->grid;
    EXPECT_TRUE(e.sparse());
    EXPECT_FALSE(e.collide);
    EXPECT_EQ(e.collideBones, std::vector<std::string>{"foot_r"});
    EXPECT_FLOAT_EQ(e.collideThickness, 0.1f);
}

// The built-in default is docs/scenes/hero.json: the combo, toon, its three effects, post on.
TEST(SceneFile, DefaultSceneIsTheHeroCombo) {
    const scene::Scene s = scene::defaultScene();
    Result<scene::Scene> file =
        scene::loadScene(std::string(MFX_SOURCE_DIR) + "/docs/scenes/hero.json");
    ASSERT_TRUE(file) << file.error().message;
    ASSERT_EQ(s.effects.size(), 3u);
    ASSERT_EQ(file.value().effects.size(), 3u);
    for (size_t e = 0; e < 3; ++e)
        EXPECT_EQ(s.effects[e].name, file.value().effects[e].name);
    EXPECT_EQ(s.effects[0].name, "kick lines");
    EXPECT_EQ(s.effects[1].name, "slash arc");
    EXPECT_TRUE(s.effects[1].as<scene::SpeedLinesSpec>()->ribbon.sheet); // the sword's sweep
    EXPECT_EQ(s.effects[2].as<scene::SmokeSpec>()->shading.preset, scene::SmokePreset::Energy);
    EXPECT_EQ(scene::characterStyle(s.characters[0]), scene::CharacterStyle::Toon);
    EXPECT_GT(s.post.bloom, 0.0f);
    EXPECT_EQ(s.post.toneMap, scene::ToneMap::Aces);
    const Result<anim::Character> c = scene::loadCharacter(s);
    ASSERT_TRUE(c.ok()) << c.error().message;
    EXPECT_EQ(scene::sceneClip(s.characters[0], c.value()).name, "kick_slash");
}

TEST(SceneFile, KickSceneIsTheKickWithLinesBlurAndSmoke) {
    const scene::Scene s = scene::kickScene();
    ASSERT_EQ(s.effects.size(), 3u);
    EXPECT_TRUE(s.effects[0].is<scene::SpeedLinesSpec>());
    EXPECT_TRUE(s.effects[1].is<scene::MotionBlurSpec>());
    EXPECT_TRUE(s.effects[2].is<scene::SmokeSpec>());
    const Result<anim::Character> c = scene::loadCharacter(s);
    ASSERT_TRUE(c.ok()) << c.error().message;
    EXPECT_EQ(scene::sceneClip(s.characters[0], c.value()).name, "roundhouse_kick");
}

TEST(SceneFile, ReadmeExampleParses) {
    // The README's complete example, between the markers around its ```json block.
    std::ifstream in(std::string(MFX_SOURCE_DIR) + "/README.md");
    std::stringstream text;
    text << in.rdbuf();
    const std::string readme = text.str();
    const std::string open = "<!-- scene example -->\n```json\n";
    const size_t begin = readme.find(open);
    ASSERT_NE(begin, std::string::npos) << "README.md has no marked scene example";
    const size_t end = readme.find("```", begin + open.size());
    std::string example = readme.substr(begin + open.size(), end - begin - open.size());
    // The example is commented with // lines, which the README explains are not JSON.
    std::stringstream lines(example);
    std::string line, json;
    while (std::getline(lines, line)) {
        const size_t comment = line.find("//");
        json += (comment == std::string::npos ? line : line.substr(0, comment)) + "\n";
    }
    const scene::Scene s = parse(json);
    EXPECT_TRUE(scene::checkNames(s, anim::makeFighter()).ok());
    EXPECT_GE(s.effects.size(), 4u);
}

// --- Malformed scenes
// ------------------------------------------------------------------------------

struct BadScene {
    const char* name;
    const char* json;
    const char* expected; // a part of the one-line error
    bool needsCharacter = false;
};

const BadScene kBadScenes[] = {
    {"NotJson", "{\"effects\": [", "test.json: not valid JSON: "},
    {"NotAnObject", "[1, 2]", "test.json: scene: expected an object, got an array"},
    {"NoEffects", "{}", "test.json: effects: missing"},
    {"EffectsNotAnArray", R"({"effects": {"type": "smoke"}})",
     "effects: expected an array of effects, got an object"},
    {"UnknownTopKey", R"({"effects": [], "camra": {}})",
     "camra: unknown key; keys here are: character, characters, camera"},
    {"EffectWithoutType", R"({"effects": [{"bones": ["foot_r"]}]})", "effects[0].type: missing"},
    {"UnknownEffectType", R"({"effects": [{"type": "sparkles"}]})",
     "effects[0].type: \"sparkles\" is not one of: speed_lines, motion_blur"},
    {"WrongValueType", R"({"effects": [{"type": "smoke", "fade": "fast"}]})",
     "effects[0].fade: expected a number, got a string"},
    {"OutOfRange", R"({"output": {"fps": 0}, "effects": []})", "output.fps: 0 is outside [1, 240]"},
    {"GridNotWhole", R"({"effects": [{"type": "smoke", "grid": [32, 32.5, 32]}]})",
     "effects[0].grid[1]: expected a whole number"},
    {"GridTooSmall", R"({"effects": [{"type": "smoke", "grid": [2, 32, 32]}]})",
     "effects[0].grid[0]: 2 is outside [4, 256]"},
    {"SparseGridTooLarge",
     R"({"effects": [{"type": "smoke", "domain": "sparse", "grid": [4096, 64, 64]}]})",
     "effects[0].grid[0]: 4096 is outside [8, 2048]"},
    {"DenseGridPastTheDenseLimit", R"({"effects": [{"type": "smoke", "grid": [512, 64, 64]}]})",
     "effects[0].grid[0]: 512 is outside [4, 256]"},
    {"UnknownDomain", R"({"effects": [{"type": "smoke", "domain": "adaptive"}]})",
     "effects[0].domain: \"adaptive\" is not one of: dense, sparse"},
    {"MaxBricksOnADenseGrid", R"({"effects": [{"type": "smoke", "max_bricks": 100}]})",
     "effects[0].max_bricks: only for \"domain\": \"sparse\""},
    {"OriginOnADenseGrid", R"({"effects": [{"type": "smoke", "origin": [0, 0, 0]}]})",
     "effects[0].origin: only for \"domain\": \"sparse\""},
    {"LiveSpeedOnADenseGrid", R"({"effects": [{"type": "smoke", "live_speed": 0.5}]})",
     "effects[0].live_speed: only for \"domain\": \"sparse\""},
    {"ZeroMaxBricks", R"({"effects": [{"type": "smoke", "domain": "sparse", "max_bricks": 0}]})",
     "effects[0].max_bricks: 0 is outside 1..1048576"},
    {"SparseWithMultigrid",
     R"({"effects": [{"type": "smoke", "domain": "sparse", "pressure": "multigrid"}]})",
     "effects[0].pressure: only for \"domain\": \"dense\" (the sparse domain solves with jacobi"},
    {"SparseWithBfecc",
     R"({"effects": [{"type": "smoke", "domain": "sparse", "advection": "bfecc"}]})",
     "effects[0].advection: only for \"domain\": \"dense\""},
    {"SparseWithFp16", R"({"effects": [{"type": "smoke", "domain": "sparse", "storage": "fp16"}]})",
     "effects[0].storage: only for \"domain\": \"dense\""},
    {"SparseWithVorticity",
     R"({"effects": [{"type": "smoke", "domain": "sparse", "vorticity": 0.5}]})",
     "effects[0].vorticity: only for \"domain\": \"dense\""},
    {"SparseFollowing", R"({"effects": [{"type": "smoke", "domain": "sparse", "follow": true}]})",
     "effects[0].follow: only for \"domain\": \"dense\""},
    {"NegativeCollideThickness",
     R"({"effects": [{"type": "smoke", "collide": true, "collide_thickness": -1}]})",
     "effects[0].collide_thickness: -1 is outside"},
    {"SmokeKeyOnSpeedLines", R"({"effects": [{"type": "speed_lines", "jacobi": 20}]})",
     "effects[0].jacobi: not a key of speed_lines effects"},
    {"UnknownEffectKey", R"({"effects": [{"type": "motion_blur", "colour_": [1, 0, 0]}]})",
     "effects[0].colour_: unknown key; keys here are: type, name, character, bones"},
    {"EndBeforeStart", R"({"effects": [{"type": "smoke", "start": 2, "end": 1}]})",
     "effects[0].end: 1 is not after start (2)"},
    {"CameraLooksNowhere",
     R"({"camera": {"position": [1, 1, 1], "target": [1, 1, 1]}, "effects": []})",
     "camera.target: is where the camera is"},
    {"ColourTooShort", R"({"effects": [{"type": "speed_lines", "colour": [1, 0]}]})",
     "effects[0].colour: expected an array of 3 or 4 numbers, got an array of 2"},
    {"ColourTooBright", R"({"effects": [{"type": "speed_lines", "colour": [1.5, 0, 0]}]})",
     "effects[0].colour[0]: 1.5 is outside [0, 1]"},
    {"BonesNotAnArray", R"({"effects": [{"type": "smoke", "bones": "foot_r"}]})",
     "effects[0].bones: expected an array of names, got a string"},
    {"BoneNotAName", R"({"effects": [{"type": "smoke", "bones": [3]}]})",
     "effects[0].bones[0]: expected a name, got a number"},
    {"HugeNumber", R"({"effects": [{"type": "smoke", "fade": 1e999}]})",
     "test.json: not valid JSON: number overflow parsing '1e999'"},
    {"DuplicateEffectNames",
     R"({"effects": [{"type": "smoke", "name": "a"}, {"type": "speed_lines", "name": "a"}]})",
     "effects[1].name: \"a\" is the name of an earlier effect"},
    {"LoopNotBoolean", R"({"character": {"loop": 1}, "effects": []})",
     "character.loop: expected true or false, got a number"},
    {"UnknownSmokeLook", R"({"effects": [{"type": "smoke", "look": "plasma"}]})",
     "effects[0].look: \"plasma\" is not one of: smoke, fire, energy"},
    {"OneCelBand", R"({"effects": [{"type": "smoke", "cel_bands": 1}]})",
     "effects[0].cel_bands: 1 is outside 2..4"},
    {"UnknownToneMap", R"({"post": {"tone_map": "filmic"}, "effects": []})",
     "post.tone_map: \"filmic\" is not one of: aces, none"},
    {"BloomAboveOne", R"({"post": {"bloom": 1.5}, "effects": []})",
     "post.bloom: 1.5 is outside [0, 1]"},
    {"UnknownPostKey", R"({"post": {"gamma": 2.2}, "effects": []})",
     "post.gamma: unknown key; keys here are: exposure, bloom, tone_map"},
    {"TinyOutput", R"({"output": {"width": 10}, "effects": []})",
     "output.width: 10 is outside 16..8192"},
    {"FractionalFrames", R"({"output": {"frames": 2.5}, "effects": []})",
     "output.frames: expected a whole number"},
    {"UnknownEmission", R"({"effects": [{"type": "smoke", "emission": "sparse"}]})",
     "effects[0].emission: \"sparse\" is not one of: vertices, surface"},
    {"ZeroLightDirection", R"({"lights": [{"direction": [0, 0, 0]}], "effects": []})",
     "lights[0].direction: must not be zero"},
    {"UnknownBone",
     R"({"effects": [{"type": "speed_lines"}, {"type": "motion_blur"},
                     {"type": "smoke", "bones": ["hand_X"]}]})",
     "effects[2].bones[0]: no bone or bone group \"hand_X\"; groups are: right_leg, left_leg",
     true},
    {"UnknownBonePattern", R"({"effects": [{"type": "smoke", "bones": ["mixamorig:*"]}]})",
     "effects[0].bones[0]: pattern \"mixamorig:*\" matches no bone; bones are: hips, spine", true},
    {"UnknownMesh", R"({"effects": [{"type": "motion_blur", "meshes": ["cape"]}]})",
     "effects[0].meshes[0]: no mesh \"cape\"; meshes are: body, sword", true},
    {"UnknownClip", R"({"character": {"clip": "moonwalk"}, "effects": []})",
     "character.clip: no clip \"moonwalk\"; clips are: idle, roundhouse_kick", true},
    {"StartPastTheClip", R"({"character": {"start": 5}, "effects": []})",
     "character.start: 5 is not before the end of clip \"roundhouse_kick\"", true},
    {"MissingCharacterFile", R"({"character": {"source": "nowhere/dancer.glb"}, "effects": []})",
     "character.source: ", true},
};

void PrintTo(const BadScene& bad, std::ostream* os) {
    *os << bad.name;
}

class SceneFileRefuses : public ::testing::TestWithParam<BadScene> {};

TEST_P(SceneFileRefuses, WithOneLineNamingTheKey) {
    const BadScene& bad = GetParam();
    Result<scene::Scene> parsed = scene::parseScene(bad.json, "test.json");
    std::string message;
    if (bad.needsCharacter) {
        ASSERT_TRUE(parsed.ok()) << parsed.error().message;
        const Result<anim::Character> character = scene::loadCharacter(parsed.value());
        ASSERT_FALSE(character.ok()) << bad.name << " was accepted";
        message = character.error().message;
    } else {
        ASSERT_FALSE(parsed.ok()) << bad.name << " was accepted";
        message = parsed.error().message;
    }
    EXPECT_NE(message.find(bad.expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind("test.json: ", 0), 0u) << message;
}

INSTANTIATE_TEST_SUITE_P(Table, SceneFileRefuses, ::testing::ValuesIn(kBadScenes),
                         [](const ::testing::TestParamInfo<BadScene>& p) {
                             return std::string(p.param.name);
                         });

TEST(SceneFile, UnreadableFilesAreNamed) {
    const Result<scene::Scene> missing = scene::loadScene("/nonexistent/scene.json");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("/nonexistent/scene.json"), std::string::npos);
    const Result<scene::Scene> directory = scene::loadScene(MFX_TEST_OUTPUT_DIR);
    ASSERT_FALSE(directory.ok());
    EXPECT_NE(directory.error().message.find("is a directory"), std::string::npos);
}

} // namespace
} // namespace mfx::test
