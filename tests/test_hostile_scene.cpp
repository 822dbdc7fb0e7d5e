// Scene files as a hostile user writes them: each of the input classes that once crashed, hung or
// overflowed (a value nested a million levels deep where a string is expected, a number that is
// in range as a double but not as the float it is stored in, a clip slowed until the scene lasts
// for days) gets one line naming the key and the limit, and the work a long scene costs at set-up
// stays bounded.
#include "core/anim/fighter.h"
#include "core/scene/scene.h"
#include "core/scene/scene_fit.h"

#include "tests/cli_run.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <utility>
#include <vector>

namespace mfx::test {
namespace {

#define EXPECT_CONTAINS(text, part)                                                                \
    EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

// The one-line refusal of `text`; fails the test when it parses.
std::string refusal(const std::string& text) {
    const Result<scene::Scene> s = scene::parseScene(text, "hostile.json");
    EXPECT_FALSE(s.ok());
    if (s) return {};
    EXPECT_EQ(s.error().message.find('\n'), std::string::npos) << s.error().message;
    EXPECT_EQ(s.error().message.rfind("hostile.json: ", 0), 0u) << s.error().message;
    return s.error().message;
}

std::string nested(size_t levels, const std::string& inside = "\"aces\"") {
    return std::string(levels, '[') + inside + std::string(levels, ']');
}

TEST(HostileScene, ChoiceKeyNestedAMillionLevelsIsRefused) {
    // Once a SIGSEGV: the choice reader copied the value before looking at its type.
    EXPECT_CONTAINS(refusal(R"({"post": {"tone_map": )" + nested(1000000) +
                            R"(}, "effects": [{"type": "speed_lines"}]})"),
                    "nests deeper than 32 levels");
    EXPECT_CONTAINS(refusal(R"({"effects": [{"type": )" + nested(1000000) + "}]}"),
                    "nests deeper than 32 levels");
}

TEST(HostileScene, NestingWithinTheBoundStillNamesTheKey) {
    // 20 levels pass the bound: the reader then refuses the array without copying it.
    EXPECT_CONTAINS(refusal(R"({"post": {"tone_map": )" + nested(20) +
                            R"(}, "effects": [{"type": "speed_lines"}]})"),
                    "post.tone_map: expected a string, got an array");
}

TEST(HostileScene, ManyValuesAreRefusedBeforeParsing) {
    std::string many = "[";
    for (int i = 0; i < 70000; ++i)
        many += "[],";
    many += "0]";
    EXPECT_CONTAINS(refusal(R"({"effects": )" + many + "}"), "values");
}

TEST(HostileScene, NumberThatIsZeroAsAFloatIsRefused) {
    // 1e-300 is in (0, 100] as a double; stored as a float it is 0, and the frame count divided
    // by it overflowed.
    EXPECT_CONTAINS(
        refusal(R"({"character": {"speed": 1e-300}, "effects": [{"type": "speed_lines"}]})"),
        "character.speed: 1e-300 is outside (0, 100] as a 32-bit float (it becomes 0)");
    EXPECT_CONTAINS(refusal(R"({"effects": [{"type": "smoke", "cell_size": 1e-50}]})"),
                    "effects[0].cell_size: 1e-50 is outside (0, 10] as a 32-bit float");
    EXPECT_CONTAINS(refusal(R"({"effects": [{"type": "speed_lines", "width": 1e-46}]})"),
                    "effects[0].width: 1e-46 is outside (0, 1] as a 32-bit float");
}

TEST(HostileScene, BoundsHoldAsFloatsToo) {
    // A bound that is not exact in float (0.9) still admits itself.
    const Result<scene::Scene> s = scene::parseScene(
        R"({"effects": [{"type": "smoke", "anisotropy": 0.9, "fade": 1e-30}]})", "ok.json");
    EXPECT_TRUE(s.ok()) << s.error().message;
}

scene::Scene withSpeed(const std::string& speed) {
    Result<scene::Scene> s = scene::parseScene(R"({"character": {"speed": )" + speed +
                                                   R"(}, "effects": [{"type": "speed_lines"}]})",
                                               "slow.json");
    EXPECT_TRUE(s.ok()) << s.error().message;
    return s ? std::move(s).value() : scene::Scene{};
}

TEST(HostileScene, SceneLongerThanTheFrameLimitIsRefused) {
    const anim::Character fighter = anim::makeFighter();
    // The kick is 0.9 s: at speed 1e-6 it lasts 27 million frames at 30 fps.
    scene::Scene s = withSpeed("1e-6");
    const Status checked = scene::checkNames(s, fighter);
    ASSERT_FALSE(checked.ok());
    EXPECT_CONTAINS(checked.error().message,
                    "slow.json: character.speed: clip \"roundhouse_kick\"");
    EXPECT_CONTAINS(checked.error().message, "at most 100000");
    // frameCount stays defined and bounded for a caller that did not check.
    EXPECT_EQ(scene::frameCount(s, fighter), scene::kMaxFrames);
    // output.frames decides the length instead: then the slow clip is fine.
    s.output.frames = 10;
    EXPECT_TRUE(scene::checkNames(s, fighter).ok());
    EXPECT_EQ(scene::frameCount(s, fighter), 10u);
}

TEST(HostileScene, SceneAtTheFrameLimitIsAccepted) {
    const anim::Character fighter = anim::makeFighter();
    const scene::Scene s = withSpeed("0.0002701"); // 0.9 s x 30 fps / 0.0002701: 99963 frames
    const Status checked = scene::checkNames(s, fighter);
    EXPECT_TRUE(checked.ok()) << checked.error().message;
    EXPECT_EQ(scene::frameCount(s, fighter), 99963u);
}

TEST(HostileScene, LiveSampledFramesAreBoundedAndSpanTheWindow) {
    const scene::Scene s = withSpeed("0.0002701");
    const std::vector<uint32_t> frames =
        scene::liveSampledFrames(s, s.effects[0], scene::kMaxFrames);
    ASSERT_EQ(frames.size(), scene::kMaxSampledFrames);
    EXPECT_EQ(frames.front(), 0u);
    EXPECT_EQ(frames.back(), scene::kMaxFrames - 1);
    EXPECT_TRUE(std::is_sorted(frames.begin(), frames.end()));
    // A short scene is sampled at every frame.
    EXPECT_EQ(scene::liveSampledFrames(s, s.effects[0], 27).size(), 27u);
}

TEST(HostileScene, LongSceneWithManyAutomaticEffectsIsListedQuickly) {
    // Once hours: binding each effect to its fastest limb sampled a pose at every frame for
    // every limb. 64 effects over 99963 frames took the code before the bound about 30 s (16 of
    // them: 7.4 s, measured); now about 0.5 s, however long the scene. The timeout is a hang guard
    // with a wide margin, not a speed target (the sanitizer pass leaves this test out).
    std::string effects;
    for (int i = 0; i < 64; ++i)
        effects += std::string(i ? "," : "") + R"({"type": "speed_lines"})";
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/hostile_scene";
    std::filesystem::create_directories(dir);
    const std::string path = dir + "/long.json";
    std::ofstream(path) << R"({"character": {"speed": 0.0002701}, "effects": [)" + effects + "]}";
    const RunResult r = runMotionfx("scene \"" + path + "\"", "timeout 10");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_CONTAINS(r.out, "99963 frames");
}

// The program on each hostile scene: exit 1 and one line naming the file, the key and the limit.
TEST(HostileScene, ProgramRefusesEachInOneLine) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/hostile_scene";
    std::filesystem::create_directories(dir);
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"({"effects": [{"type": )" + nested(1000000) + "}]}",
         "deep.json: the JSON nests deeper than 32 levels of arrays and objects"},
        {R"({"character": {"speed": 1e-300}, "effects": [{"type": "speed_lines"}]})",
         "tiny.json: character.speed: 1e-300 is outside (0, 100] as a 32-bit float"},
        {R"({"character": {"speed": 1e-6}, "effects": [{"type": "speed_lines"}]})",
         "slow.json: character.speed: clip \"roundhouse_kick\""},
    };
    const char* names[] = {"deep.json", "tiny.json", "slow.json"};
    for (size_t i = 0; i < cases.size(); ++i) {
        const std::string path = dir + "/" + names[i];
        std::ofstream(path) << cases[i].first;
        const RunResult r = runMotionfx("scene \"" + path + "\"", "timeout 60");
        EXPECT_EQ(r.exitCode, 1) << names[i];
        EXPECT_EQ(lineCount(r.err), 1u) << r.err;
        EXPECT_CONTAINS(r.err, cases[i].second);
    }
}

TEST(HostileScene, EndlessDeviceIsRefusedNotRead) {
    // /dev/zero never ends: once read until memory ran out.
    const Result<std::string> text = scene::readSceneText("/dev/zero");
    ASSERT_FALSE(text.ok());
    EXPECT_EQ(text.error().message, "/dev/zero: not a regular file");
    const RunResult r = runMotionfx("scene /dev/zero", "timeout 60");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_CONTAINS(r.err, "/dev/zero: not a regular file");
}

} // namespace
} // namespace mfx::test
