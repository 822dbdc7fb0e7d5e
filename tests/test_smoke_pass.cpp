// The smoke pass: a ball of pigment in front of the fighter covers it, the same ball behind it is
// hidden by it.
#include "core/anim/fighter.h"
#include "core/gpu/commands.h"
#include "fluid/smoke_solver.h"
#include "render/character_pass.h"
#include "render/image_output.h"
#include "render/smoke_pass.h"
#include "tests/gpu_test.h"

namespace mfx::test {
namespace {

using SmokePassTest = GpuTest;

constexpr uint32_t kWidth = 200, kHeight = 150;

// A solver whose pigment is a ball of radius `radius` cells, white, full alpha in its middle.
std::unique_ptr<fluid::SmokeSolver> ball(gpu::Context& ctx, float radius) {
    fluid::SolverOptions options;
    options.grid = {16, 16, 16, 0.05f};
    auto solver = fluid::SmokeSolver::create(ctx, options).value();
    fluid::FieldState state = fluid::FieldState::zero(options.grid);
    for (uint32_t z = 0; z < 16; ++z)
        for (uint32_t y = 0; y < 16; ++y)
            for (uint32_t x = 0; x < 16; ++x) {
                const glm::vec3 d = glm::vec3(x, y, z) + 0.5f - 8.0f;
                const float a = glm::clamp(1.5f * (1.0f - glm::length(d) / radius), 0.0f, 1.0f);
                const size_t i = options.grid.index(x, y, z) * 4;
                state.pigment[i + 0] = state.pigment[i + 1] = state.pigment[i + 2] = a;
                state.pigment[i + 3] = a;
            }
    solver->setState(state);
    return solver;
}

struct Shot {
    std::vector<uint8_t> rgba;
    std::vector<float> depth;
    std::vector<float> linear; // the target's linear RGBA
};

// The fighter in its idle pose seen from the front, and the ball centred at `centre`.
Shot shoot(gpu::Context& ctx, const fluid::SmokeSolver* smoke, glm::vec3 centre,
           const render::SmokeLook& look, const std::string& png,
           const scene::SmokeShading& shading = {}, float keyLight = 1.0f) {
    const anim::Character fighter = anim::makeFighter();
    scene::Scene s = scene::defaultScene();
    s.camera.position = glm::vec3(0.0f, 1.0f, 4.0f);
    s.camera.target = glm::vec3(0.0f, 0.8f, 0.0f);
    // Lit: the chest a mid tone that white smoke in front visibly brightens (the toon style's lit
    // band is near white there).
    s.character.style = scene::CharacterStyle::Lit;
    s.lights[0].intensity = keyLight;
    const render::SceneCamera camera = render::makeCamera(s.camera, float(kWidth) / kHeight);
    render::RenderTarget target = render::createRenderTarget(ctx, kWidth, kHeight);
    render::CharacterPass scenePass(ctx, fighter, s);
    render::SmokePass smokePass(ctx);
    const anim::Pose pose = anim::samplePose(fighter, fighter.findClip("idle"), 0.0f);
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        scenePass.skin(cmd, pose, glm::mat4(1.0f));
        render::beginRendering(cmd, target, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        scenePass.draw(cmd, camera);
        render::endRendering(cmd);
        if (smoke) {
            const render::SmokePass::Volume volume{&smoke->pigmentImage(), smoke->options().grid,
                                                   centre - glm::vec3(0.4f), shading};
            smokePass.draw(cmd, target, std::span(&volume, 1), camera, s.lights[0], look);
        }
    });
    Shot shot{render::readColor(ctx, target), render::readDepth(ctx, target),
              render::readLinearColor(ctx, target)};
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/smoke_pass";
    EXPECT_TRUE(render::ensureOutputDirectory(dir).ok());
    EXPECT_TRUE(render::writePng(dir + "/" + png, kWidth, kHeight, shot.rgba).ok());
    return shot;
}

Shot shoot(gpu::Context& ctx, const fluid::SmokeSolver* smoke, glm::vec3 centre, float fade,
           const std::string& png) {
    render::SmokeLook look;
    look.fadeDistance = fade;
    return shoot(ctx, smoke, centre, look, png);
}

// The largest difference of any channel, and the fraction of pixels differing by more than 16.
struct ShotDifference {
    int largest = 0;
    double fractionOver16 = 0.0;
};

ShotDifference difference(const Shot& a, const Shot& b) {
    ShotDifference d;
    size_t over = 0;
    for (size_t p = 0; p < a.rgba.size() / 4; ++p) {
        int worst = 0;
        for (size_t c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(int(a.rgba[p * 4 + c]) - int(b.rgba[p * 4 + c])));
        d.largest = std::max(d.largest, worst);
        over += worst > 16 ? 1 : 0;
    }
    d.fractionOver16 = double(over) / double(a.rgba.size() / 4);
    return d;
}

float brightness(const std::vector<uint8_t>& rgba, uint32_t x, uint32_t y) {
    const size_t i = (size_t(y) * kWidth + x) * 4;
    return float(rgba[i] + rgba[i + 1] + rgba[i + 2]) / 3.0f;
}

TEST_F(SmokePassTest, InFrontCoversTheFighterBehindIsHidden) {
    const auto smoke = ball(ctx(), 6.0f);
    const Shot plain = shoot(ctx(), nullptr, {}, 0.1f, "plain.png");
    const Shot front = shoot(ctx(), smoke.get(), glm::vec3(0.0f, 1.1f, 0.7f), 0.1f, "front.png");
    const Shot behind = shoot(ctx(), smoke.get(), glm::vec3(0.0f, 1.1f, -0.7f), 0.1f, "behind.png");
    // The chest's pixel: white smoke in front brightens it; behind, the chest hides the smoke.
    const uint32_t x = kWidth / 2, y = uint32_t(0.36f * kHeight);
    ASSERT_LT(plain.depth[size_t(y) * kWidth + x], 1.0f) << "the chest is there";
    const float before = brightness(plain.rgba, x, y);
    std::printf("chest pixel: %.0f plain, %.0f smoke in front, %.0f smoke behind\n", double(before),
                double(brightness(front.rgba, x, y)), double(brightness(behind.rgba, x, y)));
    EXPECT_GT(brightness(front.rgba, x, y), before + 40.0f);
    EXPECT_NEAR(brightness(behind.rgba, x, y), before, 2.0f);
}

// A dense block of smoke sunk into the floor. Marching only up to the floor would cut the smoke
// where it meets the floor: the rows just above the contact line go from no smoke to a lot within
// a row or two. With the depth fade (b = 0.15 m) smoke a little behind the floor still counts,
// faded, so the same rows change gradually: a smaller largest row-to-row step.
TEST_F(SmokePassTest, SmokeMeetsTheFloorSoftly) {
    fluid::SolverOptions options;
    options.grid = {16, 16, 16, 0.05f};
    auto block = fluid::SmokeSolver::create(ctx(), options).value();
    fluid::FieldState state = fluid::FieldState::zero(options.grid);
    for (size_t c = 0; c < state.pigment.size(); ++c)
        state.pigment[c] = 1.0f; // white, alpha 1
    block->setState(state);
    // Its centre 0.2 m above the floor: the floor cuts it 0.2 m above its bottom.
    const glm::vec3 centre(-0.9f, 0.2f, 0.5f);
    const Shot plain = shoot(ctx(), nullptr, {}, 0.1f, "floor_plain.png");
    const Shot soft = shoot(ctx(), block.get(), centre, 0.15f, "floor_soft.png");
    const Shot hard = shoot(ctx(), block.get(), centre, 0.0005f, "floor_hard.png");
    scene::Scene s = scene::defaultScene();
    s.camera.position = glm::vec3(0.0f, 1.0f, 4.0f);
    s.camera.target = glm::vec3(0.0f, 0.8f, 0.0f);
    const render::SceneCamera camera = render::makeCamera(s.camera, float(kWidth) / kHeight);
    // Where the block's front face meets the floor, under its centre.
    const glm::vec4 clip = camera.viewProjection * glm::vec4(centre.x, 0.0f, centre.z + 0.4f, 1.0f);
    const uint32_t x = uint32_t((clip.x / clip.w * 0.5f + 0.5f) * kWidth);
    const int contact = int((0.5f - clip.y / clip.w * 0.5f) * kHeight);
    auto largestStep = [&](const Shot& shot) {
        float worst = 0.0f;
        for (int y = contact - 8; y <= contact + 2; ++y) {
            auto added = [&](int row) {
                return brightness(shot.rgba, x, uint32_t(row)) -
                       brightness(plain.rgba, x, uint32_t(row));
            };
            worst = std::max(worst, std::abs(added(y) - added(y - 1)));
        }
        return worst;
    };
    const float softStep = largestStep(soft), hardStep = largestStep(hard);
    std::printf("contact row %d: largest row-to-row step of the smoke's brightness %.1f with the "
                "fade, %.1f without\n",
                contact, double(softStep), double(hardStep));
    EXPECT_GT(hardStep, 20.0f); // without the fade there is an edge to soften
    EXPECT_LT(softStep, 0.6f * hardStep);
}

// A grid without pigment leaves the picture as it was.
TEST_F(SmokePassTest, EmptyGridDrawsNothing) {
    const auto empty = ball(ctx(), 0.0f);
    const Shot plain = shoot(ctx(), nullptr, {}, 0.1f, "plain.png");
    const Shot drawn = shoot(ctx(), empty.get(), glm::vec3(0.0f, 1.1f, 0.7f), 0.1f, "empty.png");
    EXPECT_EQ(difference(plain, drawn).largest, 0);
}

// Marching only the box of cells that hold pigment gives the picture a march through the whole
// grid gives (a threshold below zero counts every cell): the samples sit at the same places.
TEST_F(SmokePassTest, MarchingThePigmentBoxOnlyChangesNothing) {
    const auto smoke = ball(ctx(), 4.0f);
    render::SmokeLook box, grid;
    box.resolution = grid.resolution = render::SmokeResolution::Full;
    grid.pigmentThreshold = -1.0f;
    const glm::vec3 centre(0.3f, 1.1f, 0.5f);
    const Shot boxed = shoot(ctx(), smoke.get(), centre, box, "box.png");
    const Shot whole = shoot(ctx(), smoke.get(), centre, grid, "whole_grid.png");
    EXPECT_LE(difference(boxed, whole).largest, 1);
}

// The half-resolution fluid buffer, upsampled by depth, looks like the full-resolution march: in
// front of the fighter, behind it (its silhouette cuts the smoke) and sunk into the floor.
TEST_F(SmokePassTest, HalfResolutionLooksLikeFull) {
    const auto smoke = ball(ctx(), 6.0f);
    int index = 0;
    for (const glm::vec3 centre : {glm::vec3(0.0f, 1.1f, 0.7f), glm::vec3(0.2f, 1.1f, -0.3f),
                                   glm::vec3(-0.5f, 0.2f, 0.5f)}) {
        const std::string name = std::to_string(index++);
        render::SmokeLook full, half;
        full.resolution = render::SmokeResolution::Full;
        half.resolution = render::SmokeResolution::Half;
        const Shot a = shoot(ctx(), smoke.get(), centre, full, "full_" + name + ".png");
        const Shot b = shoot(ctx(), smoke.get(), centre, half, "half_" + name + ".png");
        const ShotDifference d = difference(a, b);
        std::printf("ball at (%.1f, %.1f, %.1f): half against full resolution, largest difference "
                    "%d, %.3f%% of pixels beyond 16\n",
                    double(centre.x), double(centre.y), double(centre.z), d.largest,
                    100.0 * d.fractionOver16);
        EXPECT_LT(d.fractionOver16, 0.002);
    }
}

// The presets in the dark (key light off), the ball in front of the fighter: plain smoke has no
// light of its own and shows black; fire and energy glow, in their ramps' colours, brighter than
// white at the dense middle, and fire is redder at the thin rim than in its dense middle.
TEST_F(SmokePassTest, FireAndEnergyGlowInTheDark) {
    const auto smoke = ball(ctx(), 6.0f);
    const glm::vec3 centre(0.0f, 1.1f, 0.7f);
    auto shot = [&](scene::SmokePreset preset, const std::string& png) {
        return shoot(ctx(), smoke.get(), centre, render::SmokeLook{}, png,
                     scene::smokeShading(preset), 0.0f);
    };
    const Shot plain = shot(scene::SmokePreset::Smoke, "dark_smoke.png");
    const Shot fire = shot(scene::SmokePreset::Fire, "dark_fire.png");
    const Shot energy = shot(scene::SmokePreset::Energy, "dark_energy.png");
    // The ball's middle on the picture, and a point near its rim (4.5 of its 6 cells out).
    const render::SceneCamera camera = render::makeCamera(
        {glm::vec3(0.0f, 1.0f, 4.0f), glm::vec3(0.0f, 0.8f, 0.0f)}, float(kWidth) / kHeight);
    auto pixelOf = [&](glm::vec3 p) {
        const glm::vec4 clip = camera.viewProjection * glm::vec4(p, 1.0f);
        const uint32_t x = uint32_t((clip.x / clip.w * 0.5f + 0.5f) * kWidth);
        const uint32_t y = uint32_t((0.5f - clip.y / clip.w * 0.5f) * kHeight);
        return (size_t(y) * kWidth + x) * 4;
    };
    const size_t middle = pixelOf(centre), rim = pixelOf(centre + glm::vec3(0.225f, 0.0f, 0.0f));
    auto rgb = [](const Shot& s, size_t p) {
        return glm::vec3(s.linear[p], s.linear[p + 1], s.linear[p + 2]);
    };
    std::cout << "middle: smoke " << glm::length(rgb(plain, middle)) << ", fire "
              << rgb(fire, middle).r << " " << rgb(fire, middle).g << " " << rgb(fire, middle).b
              << ", energy " << rgb(energy, middle).r << " " << rgb(energy, middle).g << " "
              << rgb(energy, middle).b << "; fire rim " << rgb(fire, rim).r << " "
              << rgb(fire, rim).g << "\n";
    EXPECT_LT(glm::length(rgb(plain, middle)), 0.02f) << "no light, no glow: black";
    EXPECT_GT(rgb(fire, middle).r, 1.0f) << "fire glows brighter than white";
    EXPECT_GT(rgb(fire, middle).r, rgb(fire, middle).b) << "fire is warm";
    EXPECT_GT(rgb(energy, middle).b, 1.0f) << "energy glows brighter than white";
    EXPECT_GE(rgb(energy, middle).b, rgb(energy, middle).r) << "energy is cool";
    const float hotMiddle = rgb(fire, middle).g / rgb(fire, middle).r;
    const float coolRim = rgb(fire, rim).g / std::max(rgb(fire, rim).r, 1e-6f);
    EXPECT_GT(rgb(fire, rim).r, 0.01f) << "the rim glows too";
    EXPECT_GT(hotMiddle, coolRim + 0.1f) << "yellower where denser";
}

} // namespace
} // namespace mfx::test
