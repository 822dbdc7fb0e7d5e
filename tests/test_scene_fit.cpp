// Any character, out of the box (core/scene/scene_fit.h): uniform scaling to a human height, the
// fastest limb for effects that name no bone, strides by vertex count, bone groups in scenes, and
// the automatic camera and stage. The framing tests render real characters through the motionfx
// program and judge the picture itself.
#include "core/scene/scene_fit.h"

#include "core/scene/kinds/smoke_effect.h"
#include "core/scene/kinds/trail_effects.h"

#include "core/anim/bone_groups.h"
#include "core/anim/fighter.h"
#include "core/anim/gltf_import.h"
#include "core/anim/skinning.h"
#include "core/trajectory/trajectory_source.h"
#include "render/image_output.h"
#include "tests/cli_run.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

namespace mfx::test {
namespace {

const std::string kAssets = std::string(MFX_SOURCE_DIR) + "/../shared/assets/";

scene::Scene parse(const std::string& text) {
    Result<scene::Scene> s = scene::parseScene(text, "test.json");
    EXPECT_TRUE(s.ok()) << s.error().message;
    return s ? std::move(s).value() : scene::Scene{};
}

// The stride of a trajectory effect's trail, and a smoke effect's settings.
uint32_t strideOf(const scene::EffectSpec& e) {
    const scene::TrailSpec* trail = e.kind().queue();
    EXPECT_TRUE(trail) << e.type() << " has no trail";
    return trail ? trail->stride : 0;
}
const scene::SmokeSpec& smokeOf(const scene::EffectSpec& e) {
    static const scene::SmokeSpec none;
    EXPECT_TRUE(e.is<scene::SmokeSpec>()) << e.type() << " is not smoke";
    return e.is<scene::SmokeSpec>() ? *e.as<scene::SmokeSpec>() : none;
}

float heightAtStart(const scene::Scene& s, const anim::Character& c) {
    const anim::Pose pose = anim::samplePose(c, &scene::sceneClip(s.characters[0], c),
                                             s.characters[0].start, anim::Wrap::Clamp);
    return scene::poseBounds(c, pose).size().y;
}

TEST(ScaleCharacter, EveryVertexOfEveryPoseMovesByTheFactor) {
    anim::Character fighter = anim::makeFighter();
    const anim::Clip& clip = *fighter.findClip("roundhouse_kick");
    const anim::Pose before = anim::samplePose(fighter, &clip, 0.43f);
    const std::vector<anim::SkinnedVertex> was =
        anim::skinPrimitive(fighter, fighter.meshes[0].primitives[0], before);
    anim::Character scaled = fighter;
    anim::scaleCharacter(scaled, 0.37f);
    const anim::Pose after = anim::samplePose(scaled, scaled.findClip("roundhouse_kick"), 0.43f);
    const std::vector<anim::SkinnedVertex> now =
        anim::skinPrimitive(scaled, scaled.meshes[0].primitives[0], after);
    ASSERT_EQ(was.size(), now.size());
    float worst = 0.0f, normalWorst = 0.0f;
    for (size_t v = 0; v < was.size(); ++v) {
        worst = std::max(worst, glm::length(now[v].position - 0.37f * was[v].position));
        normalWorst = std::max(normalWorst, glm::length(now[v].normal - was[v].normal));
    }
    EXPECT_LT(worst, 1e-5f);
    EXPECT_LT(normalWorst, 1e-5f);
}

TEST(CharacterScale, TheFighterIsLeftAlone) {
    const scene::Scene s = scene::kickScene();
    std::string note = "unset";
    EXPECT_EQ(scene::chooseCharacterScale(s, 0, anim::makeFighter(), "fighter", &note), 1.0f);
    EXPECT_EQ(note, "");
}

TEST(CharacterScale, OutliersAreBroughtToAHumanHeightWithANote) {
    const scene::Scene s = scene::kickScene();
    for (float factor : {0.01f, 0.2f, 3.0f, 50.0f}) {
        anim::Character c = anim::makeFighter();
        anim::scaleCharacter(c, factor);
        std::string note;
        const float chosen = scene::chooseCharacterScale(s, 0, c, "big.glb", &note);
        anim::scaleCharacter(c, chosen);
        EXPECT_NEAR(heightAtStart(s, c), scene::kDefaultHeight, 1e-3f) << factor;
        EXPECT_EQ(note.rfind("big.glb is ", 0), 0u) << note;
        EXPECT_NE(note.find(" units tall: scaled by "), std::string::npos) << note;
        EXPECT_NE(note.find(" to 1.80 m; set character.height or character.scale to change"),
                  std::string::npos)
            << note;
    }
}

TEST(CharacterScale, HeightAndScaleKeysOverrideTheDefault) {
    const anim::Character fighter = anim::makeFighter();
    scene::Scene s = parse(R"({"character": {"height": 1.2}, "effects": []})");
    std::string note;
    const float toHeight = scene::chooseCharacterScale(s, 0, fighter, "fighter", &note);
    EXPECT_NEAR(toHeight * heightAtStart(s, fighter), 1.2f, 1e-4f);
    EXPECT_NE(note.find("to 1.20 m (character.height)"), std::string::npos) << note;
    s = parse(R"({"character": {"scale": 2.5}, "effects": []})");
    EXPECT_EQ(scene::chooseCharacterScale(s, 0, fighter, "fighter", &note), 2.5f);
    EXPECT_NE(note.find("scaled by 2.5"), std::string::npos) << note;
}

TEST(CharacterScale, BadSizeKeysAreRefusedNamingTheKey) {
    const std::pair<const char*, const char*> cases[] = {
        {R"({"character": {"height": 1.8, "scale": 2}, "effects": []})",
         "character.scale: give height or scale, not both"},
        {R"({"character": {"height": -1}, "effects": []})", "character.height: -1 is outside"},
        {R"({"character": {"scale": 0}, "effects": []})", "character.scale: 0 is outside"},
        {R"({"character": {"scale": "big"}, "effects": []})", "character.scale: expected a number"},
    };
    for (const auto& [text, message] : cases) {
        const Result<scene::Scene> s = scene::parseScene(text, "test.json");
        ASSERT_FALSE(s.ok()) << text;
        EXPECT_NE(s.error().message.find(message), std::string::npos) << s.error().message;
    }
}

TEST(FitScene, AGiantOnPurposeGetsItsLengthDefaultsScaled) {
    const scene::Scene parsed = parse(R"({"character": {"height": 10}, "effects": [
        {"type": "smoke", "bones": ["foot_r"]},
        {"type": "speed_lines", "bones": ["foot_r"], "width": 0.05},
        {"type": "speed_lines", "bones": ["foot_r"], "texture": "t.png"}]})");
    scene::Scene s = parsed;
    std::string note;
    Result<anim::Character> giant = scene::loadCharacter(s, 0, &note);
    ASSERT_TRUE(giant.ok()) << giant.error().message;
    std::vector<std::string> notes;
    ASSERT_TRUE(scene::fitScene(s, giant.value(), &notes).ok());
    const float unit = 10.0f / scene::kDefaultHeight;
    EXPECT_NEAR(smokeOf(s.effects[0]).grid.cellSize,
                smokeOf(parsed.effects[0]).grid.cellSize * unit, 1e-5f);
    EXPECT_NEAR(smokeOf(s.effects[0]).radius, smokeOf(parsed.effects[0]).radius * unit, 1e-5f);
    ASSERT_TRUE(s.effects[1].is<scene::SpeedLinesSpec>());
    EXPECT_EQ(s.effects[1].as<scene::SpeedLinesSpec>()->width, 0.05f); // given: kept
    // A texture's tile scales with the width it lies on.
    const auto* textured = s.effects[2].as<scene::SpeedLinesSpec>();
    EXPECT_NEAR(textured->ribbon.texture.tileLength, scene::RibbonTexture{}.tileLength * unit,
                1e-5f);
    EXPECT_NEAR(textured->width, scene::SpeedLinesSpec{}.width * unit, 1e-5f);
    ASSERT_FALSE(notes.empty());
    EXPECT_NE(notes.back().find("the character is 10 m tall: the effects' default"),
              std::string::npos)
        << notes.back();
    EXPECT_NE(notes.back().find("texture_tile"), std::string::npos) << notes.back();
    // Fitting again scales nothing twice; a human-sized character scales nothing at all.
    const float once = smokeOf(s.effects[0]).grid.cellSize;
    ASSERT_TRUE(scene::fitScene(s, giant.value()).ok());
    EXPECT_EQ(smokeOf(s.effects[0]).grid.cellSize, once);
    scene::Scene human = parse(R"({"effects": [{"type": "smoke", "bones": ["foot_r"]}]})");
    ASSERT_TRUE(scene::fitScene(human, anim::makeFighter()).ok());
    EXPECT_EQ(smokeOf(human.effects[0]).grid.cellSize, scene::SmokeGridSpec{}.cellSize);
}

TEST(FitScene, AnEffectWithoutBonesTakesTheFastestLimb) {
    const anim::Character fighter = anim::makeFighter();
    const std::pair<const char*, const char*> cases[] = {{"roundhouse_kick", "right_leg"},
                                                         {"sword_slash", "right_arm"}};
    for (const auto& [clip, limb] : cases) {
        scene::Scene s = parse(std::string(R"({"character": {"clip": ")") + clip +
                               R"("}, "effects": [{"type": "speed_lines"}]})");
        std::vector<std::string> notes;
        ASSERT_TRUE(scene::fitScene(s, fighter, &notes).ok());
        EXPECT_EQ(s.effects[0].bones, anim::resolveBoneGroup(fighter, limb)) << clip;
        ASSERT_EQ(notes.size(), 1u);
        EXPECT_NE(notes[0].find(std::string("bound to ") + limb + ", the fastest limb"),
                  std::string::npos)
            << notes[0];
    }
}

TEST(FitScene, MeshesOrEmptyBonesKeepTheWholeSelection) {
    const anim::Character fighter = anim::makeFighter();
    scene::Scene s = parse(R"({"effects": [{"type": "speed_lines", "meshes": ["sword"]},
                                           {"type": "motion_blur", "bones": []}]})");
    ASSERT_TRUE(scene::fitScene(s, fighter).ok());
    EXPECT_TRUE(s.effects[0].bones.empty());
    EXPECT_TRUE(s.effects[1].bones.empty());
}

TEST(FitScene, GroupsAndPatternsBecomeBoneNames) {
    const anim::Character fighter = anim::makeFighter();
    scene::Scene s =
        parse(R"({"effects": [{"type": "smoke", "bones": ["right_foot", "shin_*", "foot_r"]}]})");
    ASSERT_TRUE(scene::fitScene(s, fighter).ok());
    EXPECT_EQ(s.effects[0].bones,
              (std::vector<std::string>{"foot_r", "toe_r", "shin_l", "shin_r"}));
}

TEST(FitScene, AnUnknownGroupIsRefusedWithItsKeyPath) {
    const anim::Character fighter = anim::makeFighter();
    scene::Scene s =
        parse(R"({"effects": [{"type": "smoke", "bones": ["foot_r", "right_tail"]}]})");
    const Status fitted = scene::fitScene(s, fighter);
    ASSERT_FALSE(fitted.ok());
    EXPECT_NE(fitted.error().message.find(
                  "test.json: effects[0].bones[1]: no bone or bone group \"right_tail\"; groups "
                  "are: right_leg"),
              std::string::npos)
        << fitted.error().message;
}

// The number of trail vertices an automatic stride leaves of an effect's selection.
size_t trailVertices(const anim::Character& c, const scene::EffectSpec& e) {
    trajectory::Selection selection;
    selection.bones = e.bones;
    selection.meshes = e.meshes;
    const Result<trajectory::Source> source = trajectory::selectSource(c, selection);
    EXPECT_TRUE(source.ok());
    return source ? (source.value().vertices.size() + strideOf(e) - 1) / strideOf(e) : 0;
}

// The fighter with its body primitive repeated until it has at least `vertices` vertices (a
// dense mesh with the fighter's skeleton and motion).
anim::Character denseFighter(size_t vertices) {
    anim::Character c = anim::makeFighter();
    anim::Primitive& body = c.meshes[0].primitives[0];
    const anim::Primitive one = body;
    while (body.positions.size() < vertices) {
        const uint32_t offset = uint32_t(body.positions.size());
        body.positions.insert(body.positions.end(), one.positions.begin(), one.positions.end());
        body.normals.insert(body.normals.end(), one.normals.begin(), one.normals.end());
        body.uvs.insert(body.uvs.end(), one.uvs.begin(), one.uvs.end());
        body.joints.insert(body.joints.end(), one.joints.begin(), one.joints.end());
        body.weights.insert(body.weights.end(), one.weights.begin(), one.weights.end());
        for (uint32_t i : one.indices)
            body.indices.push_back(i + offset);
    }
    return c;
}

TEST(FitScene, StridesLeaveAVisibleTrailOnSmallAndLargeMeshes) {
    const Result<anim::Character> figure = anim::importGltf(kAssets + "RiggedFigure.gltf");
    ASSERT_TRUE(figure.ok()) << figure.error().message;
    const anim::Character dense = denseFighter(30000);
    for (const anim::Character* c : {&figure.value(), &dense}) {
        size_t vertices = 0;
        for (const anim::Mesh& m : c->meshes)
            for (const anim::Primitive& p : m.primitives)
                vertices += p.positions.size();
        scene::Scene s = parse(R"({"effects": [{"type": "speed_lines"},
                                               {"type": "motion_particles"},
                                               {"type": "speed_lines", "stride": 7}]})");
        ASSERT_TRUE(scene::fitScene(s, *c).ok());
        const size_t lines = trailVertices(*c, s.effects[0]);
        const size_t particles = trailVertices(*c, s.effects[1]);
        if (vertices < 1000) { // a limb of a few dozen vertices: every one of them
            EXPECT_EQ(strideOf(s.effects[0]), 1u);
            EXPECT_GE(lines, 20u);
        } else {
            EXPECT_GE(lines, scene::kTargetLines * 2 / 3) << vertices;
            EXPECT_LE(lines, scene::kTargetLines * 3 / 2) << vertices;
            EXPECT_GE(particles, scene::kTargetParticles * 2 / 3) << vertices;
            EXPECT_LE(particles, scene::kTargetParticles * 3 / 2) << vertices;
        }
        EXPECT_EQ(strideOf(s.effects[2]), 7u); // a stride given is kept
    }
}

TEST(FitScene, ACameraGivenIsUsedAsWritten) {
    const anim::Character fighter = anim::makeFighter();
    scene::Scene s = parse(R"({"camera": {"position": [1, 2, 3], "target": [0, 1, 0]},
                               "effects": []})");
    ASSERT_TRUE(scene::fitScene(s, fighter).ok());
    EXPECT_EQ(s.camera.position, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.camera.target, glm::vec3(0, 1, 0));
    EXPECT_EQ(s.stage.floorHeight, 0.0f);
    EXPECT_FALSE(s.stage.shadowCentre.has_value());
}

class AutomaticCamera : public ::testing::TestWithParam<const char*> {};

TEST_P(AutomaticCamera, SeesTheWholeAnimationWithTheFloorUnderIt) {
    const anim::Character fighter = anim::makeFighter();
    scene::Scene s =
        parse(std::string(R"({"effects": [{"type": "speed_lines"}], )") + GetParam() + "}");
    ASSERT_TRUE(s.camera.automatic);
    ASSERT_TRUE(scene::fitScene(s, fighter).ok());
    EXPECT_FALSE(s.camera.automatic);
    const scene::Bounds bounds = scene::animatedBounds(s, fighter);
    EXPECT_FLOAT_EQ(s.stage.floorHeight, bounds.low.y);
    // Every corner of the animated bounds lies inside the view frustum.
    const glm::mat4 view = glm::lookAt(s.camera.position, s.camera.target, glm::vec3(0, 1, 0));
    const glm::mat4 projection = glm::perspective(glm::radians(s.camera.fovDegrees),
                                                  float(s.output.width) / float(s.output.height),
                                                  s.camera.nearPlane, s.camera.farPlane);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec4 p((corner & 1) ? bounds.high.x : bounds.low.x,
                          (corner & 2) ? bounds.high.y : bounds.low.y,
                          (corner & 4) ? bounds.high.z : bounds.low.z, 1.0f);
        const glm::vec4 clip = projection * view * p;
        EXPECT_LT(std::abs(clip.x / clip.w), 1.0f) << corner;
        EXPECT_LT(std::abs(clip.y / clip.w), 1.0f) << corner;
        EXPECT_GT(clip.w, s.camera.nearPlane) << corner;
    }
    // Fitting again changes nothing: the automatic choices were made once.
    const scene::Scene once = s;
    s.camera.automatic = true; // even asked to frame again, the same bounds give the same camera
    ASSERT_TRUE(scene::fitScene(s, fighter).ok());
    EXPECT_EQ(s.camera.position, once.camera.position);
    EXPECT_EQ(s.camera.target, once.camera.target);
    EXPECT_EQ(s.stage.floorHeight, once.stage.floorHeight);
    EXPECT_EQ(s.stage.backdropCentre, once.stage.backdropCentre);
    EXPECT_EQ(s.stage.shadowRadius, once.stage.shadowRadius);
    EXPECT_EQ(s.effects[0].bones, once.effects[0].bones);
    EXPECT_EQ(strideOf(s.effects[0]), strideOf(once.effects[0]));
    EXPECT_FALSE(s.effects[0].automaticBones);
    EXPECT_FALSE(s.effects[0].automaticStride);
}

INSTANTIATE_TEST_SUITE_P(
    Placements, AutomaticCamera,
    ::testing::Values(R"("output": {"width": 640, "height": 360})",
                      R"("character": {"yaw_degrees": 90, "position": [3, 0.5, -2]})",
                      R"("character": {"yaw_degrees": 200, "clip": "spin"},
                         "output": {"width": 200, "height": 800})"));

TEST(FitScene, AnEffectWhoseBonesNeverMoveIsNamed) {
    const anim::Character fighter = anim::makeFighter();
    // The kick holds its last pose after the clip ends; an effect live only then sees no motion.
    scene::Scene s = parse(R"({"output": {"frames": 40},
        "effects": [{"type": "speed_lines", "name": "late", "bones": ["foot_r"], "start": 1.0},
                    {"type": "speed_lines", "name": "kick", "bones": ["foot_r"]},
                    {"type": "motion_blur", "name": "never", "bones": ["foot_r"], "start": 9}]})");
    ASSERT_TRUE(scene::fitScene(s, fighter).ok());
    const std::vector<std::string> still = scene::motionlessEffects(s, fighter, 40);
    ASSERT_EQ(still.size(), 2u);
    EXPECT_EQ(still[0].rfind("\"late\" (its vertices never move", 0), 0u) << still[0];
    EXPECT_EQ(still[1].rfind("\"never\" (its window 9-end s is outside the render", 0), 0u)
        << still[1];
}

// ---------------------------------------------------------------------------------------------
// Through the program: any character framed, with visible effects, from one scene file.

const std::string& outputDir() {
    static const std::string dir = [] {
        const std::string d = std::string(MFX_TEST_OUTPUT_DIR) + "/scene_fit";
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

// The built-in fighter exported as glTF with `factor` written into a new root node's scale.
std::string rescaledFighter(float factor) {
    const std::string name = outputDir() + "/fighter_x" + std::to_string(factor) + ".gltf";
    if (std::filesystem::exists(name)) return name;
    // Tests run as parallel processes: each writes its own files and renames the result into
    // place (the same bytes whoever wins).
    const std::string own = std::to_string(::getpid());
    const std::string plain = outputDir() + "/fighter_" + own + ".gltf";
    const RunResult exported = runMotionfx("export-fighter \"" + plain + "\"");
    EXPECT_EQ(exported.exitCode, 0) << exported.err;
    nlohmann::json doc = nlohmann::json::parse(readFile(plain));
    nlohmann::json& roots = doc["scenes"][0]["nodes"];
    doc["nodes"].push_back(
        {{"name", "Armature"}, {"children", roots}, {"scale", {factor, factor, factor}}});
    roots = nlohmann::json::array({doc["nodes"].size() - 1});
    const std::string temporary = name + "." + own + ".part";
    std::ofstream(temporary) << doc.dump();
    std::filesystem::rename(temporary, name);
    return name;
}

// A scene with no camera and no sizes, the stage off so the background is uniform.
std::string framingScene(const std::string& name, const std::string& source,
                         const std::string& clip, const std::string& effects) {
    const std::string path = outputDir() + "/" + name + ".json";
    nlohmann::json character = {{"source", source}};
    if (!clip.empty()) character["clip"] = clip;
    const nlohmann::json doc = {{"character", character},
                                {"stage", {{"floor", false}, {"backdrop", false}}},
                                {"output", {{"width", 240}, {"height", 136}}},
                                {"effects", nlohmann::json::parse(effects)}};
    std::ofstream(path) << doc.dump(1);
    return path;
}

std::vector<render::RgbaImage> renderFrames(const std::string& scenePath, const std::string& dir) {
    std::filesystem::remove_all(dir);
    const RunResult r = runMotionfx("render \"" + scenePath + "\" --out \"" + dir + "\"");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::vector<render::RgbaImage> frames;
    for (uint32_t f = 0;; ++f) {
        char file[32];
        std::snprintf(file, sizeof file, "/frame_%04u.png", f);
        if (!std::filesystem::exists(dir + file)) break;
        Result<render::RgbaImage> image = render::readPng(dir + file);
        EXPECT_TRUE(image.ok());
        if (image) frames.push_back(std::move(image).value());
    }
    return frames;
}

bool differs(const uint8_t* a, const uint8_t* b, int threshold) {
    for (int c = 0; c < 3; ++c)
        if (std::abs(int(a[c]) - int(b[c])) > threshold) return true;
    return false;
}

struct Character {
    const char* label;
    std::string source; // "fighter", a file, or "x<factor>" for the rescaled fighter export
    const char* clip;
};

void PrintTo(const Character& c, std::ostream* os) {
    *os << c.label;
}

class CharacterFraming : public ::testing::TestWithParam<Character> {
protected:
    std::string source() const {
        const std::string s = GetParam().source;
        if (s.rfind("x", 0) == 0) return rescaledFighter(std::stof(s.substr(1)));
        return s == "fighter" ? s : kAssets + s;
    }
};

TEST_P(CharacterFraming, FillsTheFrameWithVisibleEffects) {
    const Character& c = GetParam();
    const std::string label = c.label;
    const std::vector<render::RgbaImage> alone = renderFrames(
        framingScene(label + "_alone", source(), c.clip, "[]"), outputDir() + "/" + label + "_a");
    const std::vector<render::RgbaImage> effects =
        renderFrames(framingScene(label + "_effects", source(), c.clip,
                                  R"([{"type": "speed_lines"}, {"type": "smoke"}])"),
                     outputDir() + "/" + label + "_e");
    ASSERT_FALSE(alone.empty());
    ASSERT_EQ(alone.size(), effects.size());
    size_t changed = 0, pixels = 0;
    float lowest = 1.0f, highest = 0.0f;
    for (size_t f = 0; f < alone.size(); ++f) {
        const render::RgbaImage& a = alone[f];
        const uint8_t* background = a.rgba.data(); // the top-left corner
        uint32_t top = a.height, bottom = 0;
        bool touches = false;
        for (uint32_t y = 0; y < a.height; ++y)
            for (uint32_t x = 0; x < a.width; ++x) {
                const size_t i = (size_t(y) * a.width + x) * 4;
                if (differs(&a.rgba[i], &effects[f].rgba[i], 8)) ++changed;
                ++pixels;
                if (!differs(&a.rgba[i], background, 6)) continue;
                top = std::min(top, y);
                bottom = std::max(bottom, y);
                touches |= x == 0 || y == 0 || x + 1 == a.width || y + 1 == a.height;
            }
        ASSERT_LE(top, bottom) << label << " frame " << f << ": no character in the picture";
        const float span = float(bottom - top + 1) / float(a.height);
        lowest = std::min(lowest, span);
        highest = std::max(highest, span);
        EXPECT_GE(span, 0.35f) << label << " frame " << f;
        EXPECT_LE(span, 0.95f) << label << " frame " << f;
        EXPECT_FALSE(touches) << label << " frame " << f << " touches the edge";
    }
    const double fraction = double(changed) / double(pixels);
    EXPECT_GE(fraction, 0.005) << label << ": the effects changed " << 100.0 * fraction
                               << "% of the pixels";
    std::printf("%s: %zu frames, character %.0f-%.0f%% of the frame height, effects changed "
                "%.2f%% of the pixels\n",
                label.c_str(), alone.size(), 100.0 * double(lowest), 100.0 * double(highest),
                100.0 * fraction);
}

TEST_P(CharacterFraming, TheSameRightLegSceneRunsOnIt) {
    const Character& c = GetParam();
    const std::string scenePath =
        framingScene(std::string(c.label) + "_right_leg", source(), c.clip,
                     R"([{"type": "speed_lines", "bones": ["right_leg"]},
                         {"type": "smoke", "bones": ["right_leg"]}])");
    const RunResult r = runMotionfx("simulate \"" + scenePath + "\" --frames 3");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("3 frames"), std::string::npos) << r.out;
}

INSTANTIATE_TEST_SUITE_P(Characters, CharacterFraming,
                         ::testing::Values(Character{"fighter", "fighter", ""},
                                           Character{"fighter_x0_01", "x0.01", "roundhouse_kick"},
                                           Character{"fighter_x50", "x50", "roundhouse_kick"},
                                           Character{"rigged_figure", "RiggedFigure.gltf", ""},
                                           Character{"robot_punch", "RobotExpressive.glb",
                                                     "Punch"}),
                         [](const ::testing::TestParamInfo<Character>& param) {
                             return std::string(param.param.label);
                         });

TEST(CliSceneFit, AnOutlierIsScaledWithOneLineSayingSo) {
    const std::string file = rescaledFighter(50.0f);
    const RunResult r = runMotionfx("scene \"" + file + "\" --clip roundhouse_kick");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string name = std::filesystem::path(file).filename().string();
    // About 106 units tall at its first frame (the fighter with its sword raised, times 50).
    EXPECT_NE(r.out.find(name + " is 10"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" units tall: scaled by 0.01"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("to 1.80 m; set character.height or character.scale to change\n"),
              std::string::npos)
        << r.out;
}

TEST(CliSceneFit, SceneSaysWhichLimbAnEffectWasBoundTo) {
    const std::string path = framingScene("fastest", "fighter", "", R"([{"type": "smoke"}])");
    const RunResult r = runMotionfx("scene \"" + path + "\"");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("effects[0] \"smoke#0\": bound to right_leg, the fastest limb over its "
                         "window (no bones given; peak "),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("bones: thigh_r, shin_r, foot_r, toe_r"), std::string::npos) << r.out;
}

TEST(CliSceneFit, ACharacterFileIsPreviewedWithItsClipSizeAndBones) {
    const RunResult r = runMotionfx("render \"" + kAssets +
                                    "RobotExpressive.glb\" --clip Punch --frames 2 --size 96x54 "
                                    "--out \"" +
                                    outputDir() + "/preview\"");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("RobotExpressive.glb is 4.5 units tall: scaled by 0.4 to 1.80 m"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("RobotExpressive.glb: clip \"Punch\" (0.833 s), 1.80 m tall; effects "
                         "bound to right_arm"),
              std::string::npos)
        << r.out;
    EXPECT_TRUE(std::filesystem::exists(outputDir() + "/preview/frame_0001.png"));
}

TEST(CliSceneFit, AnEffectThatNeverMovesIsNamedAtTheEnd) {
    // The fighter with only its right hand animated: an effect on the left foot has nothing to
    // draw, one on the right hand has.
    const std::string plain = rescaledFighter(1.0f);
    nlohmann::json doc = nlohmann::json::parse(readFile(plain));
    int hand = -1;
    for (size_t i = 0; i < doc["nodes"].size(); ++i)
        if (doc["nodes"][i].value("name", "") == "hand_r") hand = int(i);
    ASSERT_GE(hand, 0);
    for (nlohmann::json& animation : doc["animations"]) {
        nlohmann::json kept = nlohmann::json::array();
        for (const nlohmann::json& channel : animation["channels"])
            if (channel["target"]["node"] == hand) kept.push_back(channel);
        animation["channels"] = kept;
    }
    const std::string handOnly = outputDir() + "/hand_only.gltf";
    std::ofstream(handOnly) << doc.dump();
    const std::string path = framingScene("still", handOnly, "sword_slash",
                                          R"([{"type": "speed_lines", "name": "still feet",
                                               "bones": ["left_foot"]},
                                              {"type": "speed_lines", "name": "hand",
                                               "bones": ["right_hand"]}])");
    const RunResult r = runMotionfx("simulate \"" + path + "\"");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("note: one effect had no motion to draw: \"still feet\" (its vertices "
                         "never move in its window 0-end s)\n"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("\"hand\""), std::string::npos) << r.out;
}

} // namespace
} // namespace mfx::test
