// The trajectory effects' passes over the scene pass, made by the registry as the frame makes
// them: each drawn effect changes the picture where its trail is, and writes the picture for a
// look.
#include "core/gpu/commands.h"
#include "render/character_pass.h"
#include "render/effect_kind_pass.h"
#include "render/image_output.h"
#include "render/render_target.h"
#include "sim/scene_simulation.h"
#include "tests/gpu_test.h"

#include <glm/gtc/matrix_transform.hpp>

namespace mfx::test {
namespace {

using EffectPassTest = GpuTest;

// Renders frame `frame` of `s` (after simulating frames 0..frame) with or without its effects.
std::vector<uint8_t> renderFrame(gpu::Context& ctx, const scene::Scene& s, uint32_t frame,
                                 bool effects, const std::string& png, uint32_t* draws = nullptr) {
    const Result<anim::Character> character = scene::loadCharacter(s);
    EXPECT_TRUE(character.ok());
    auto sim = sim::SceneSimulation::create(ctx, s, character.value());
    EXPECT_TRUE(sim.ok()) << sim.error().message;
    const auto passes = render::makeEffectPasses(ctx, *sim.value(), VK_SAMPLE_COUNT_1_BIT);
    EXPECT_EQ(passes.size(), 1u); // the one kind of the scene's one effect
    for (uint32_t f = 0; f <= frame; ++f) {
        sim.value()->runFrame(f);
        gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
            for (const auto& pass : passes)
                pass->advance(cmd, *sim.value(), f);
        });
    }
    const uint32_t width = 320, height = 180;
    render::RenderTarget target = render::createRenderTarget(ctx, width, height);
    render::CharacterPass scenePass(ctx, character.value(), s);
    const render::SceneCamera camera = render::makeCamera(s.camera, float(width) / float(height));
    const float t = sim.value()->frameTime(frame);
    const anim::Pose pose = anim::samplePose(
        character.value(), &scene::sceneClip(s.characters[0], character.value()),
        scene::clipTimeAt(s.characters[0], character.value(), t), anim::Wrap::Clamp);
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        scenePass.skin(cmd, pose, glm::mat4(1.0f));
        scenePass.shadow(cmd);
        render::beginRendering(cmd, target, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        scenePass.draw(cmd, camera);
        if (effects) {
            uint32_t n = 0;
            for (const auto& pass : passes)
                n += pass->draw(cmd, *sim.value(), camera, t);
            if (draws) *draws = n;
        }
        render::endRendering(cmd);
    });
    std::vector<uint8_t> rgba = render::readColor(ctx, target);
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/effect_pass";
    EXPECT_TRUE(render::ensureOutputDirectory(dir).ok());
    EXPECT_TRUE(render::writePng(dir + "/" + png, width, height, rgba).ok());
    return rgba;
}

size_t changedPixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t n = 0;
    for (size_t i = 0; i < a.size(); i += 4) {
        int d = 0;
        for (int c = 0; c < 3; ++c)
            d = std::max(d, std::abs(int(a[i + c]) - int(b[i + c])));
        n += d > 8 ? 1 : 0;
    }
    return n;
}

void expectEffectShows(gpu::Context& ctx, const std::string& effectJson, const std::string& name) {
    Result<scene::Scene> s =
        scene::parseScene(R"({"effects": [)" + effectJson + R"(]})", name + ".json");
    ASSERT_TRUE(s.ok()) << s.error().message;
    uint32_t draws = 0;
    const auto without = renderFrame(ctx, s.value(), 13, false, name + "_without.png");
    const auto with = renderFrame(ctx, s.value(), 13, true, name + ".png", &draws);
    const size_t changed = changedPixels(without, with);
    std::printf("%s: %u draws, %zu pixels changed\n", name.c_str(), draws, changed);
    EXPECT_GT(draws, 0u);
    EXPECT_GT(changed, 200u);
}

TEST_F(EffectPassTest, SpeedLinesShow) {
    expectEffectShows(ctx(), R"({"type": "speed_lines", "bones": ["shin_r", "foot_r", "toe_r"],
                                 "stride": 2, "lifetime": 10})",
                      "speed_lines");
}

TEST_F(EffectPassTest, BlurVolumesShow) {
    expectEffectShows(ctx(), R"({"type": "motion_blur", "bones": ["shin_r", "foot_r", "toe_r"]})",
                      "motion_blur");
}

TEST_F(EffectPassTest, ParticlesShow) {
    expectEffectShows(ctx(), R"({"type": "motion_particles", "bones": ["foot_r", "toe_r"],
                                 "lifetime": 8})",
                      "motion_particles");
}

} // namespace
} // namespace mfx::test
