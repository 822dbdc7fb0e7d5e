// The smoke pass: a ball of pigment in front of the fighter covers it, the same ball behind it is
// hidden by it.
#include "core/anim/fighter.h"
#include "core/gpu/commands.h"
#include "fluid/smoke_solver.h"
#include "render/character_pass.h"
#include "render/image_output.h"
#include "render/smoke_pass.h"
#include "tests/gpu_test.h"

#include <algorithm>
#include <cmath>

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
    scene::Scene s = scene::kickScene();
    s.camera.position = glm::vec3(0.0f, 1.0f, 4.0f);
    s.camera.target = glm::vec3(0.0f, 0.8f, 0.0f);
    // Lit: the chest a mid tone that white smoke in front visibly brightens (the toon style's lit
    // band is near white there).
    s.characters[0].style = scene::CharacterStyle::Lit;
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
            const render::SmokePass::Volume volume{smoke->pigmentVolume(), smoke->options().grid,
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
    auto shootLit = [&](const fluid::SmokeSolver* smoke, float fade, const std::string& png) {
        render::SmokeLook look;
        look.fadeDistance = fade;
        // Scattering evenly and a key light of 1.5: seen from above the light's side, the
        // forwards-scattering default sends the light away from the eye, and self-shadowed
        // through all of its depth the block's bottom is dim, too faint an edge to soften.
        scene::SmokeShading even;
        even.anisotropy = 0.0f;
        return shoot(ctx(), smoke, centre, look, png, even, 1.5f);
    };
    const Shot plain = shootLit(nullptr, 0.1f, "floor_plain.png");
    const Shot soft = shootLit(block.get(), 0.15f, "floor_soft.png");
    const Shot hard = shootLit(block.get(), 0.0005f, "floor_hard.png");
    scene::Scene s = scene::kickScene();
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

// The compute march (a GPU's) draws what the fragment march (a CPU device's) draws: the same
// function per texel, over the whole fluid buffer instead of the box's faces. In front of the
// fighter, across its silhouette and sunk into the floor, at half and full resolution; the linear
// colours agree to fp16 rounding of the fluid buffer (the two shader stages may contract the
// march's arithmetic into fused multiply-adds differently).
TEST_F(SmokePassTest, TheComputeMarchDrawsWhatTheFragmentMarchDraws) {
    const auto smoke = ball(ctx(), 6.0f);
    int shots = 0;
    for (render::SmokeResolution resolution :
         {render::SmokeResolution::Half, render::SmokeResolution::Full})
        for (glm::vec3 centre : {glm::vec3(0.0f, 1.1f, 0.7f), glm::vec3(0.3f, 1.1f, -0.3f),
                                 glm::vec3(-0.5f, 0.2f, 0.5f)}) {
            render::SmokeLook fragment, compute;
            fragment.resolution = compute.resolution = resolution;
            fragment.march = render::SmokeMarch::Fragment;
            compute.march = render::SmokeMarch::Compute;
            const std::string name = "march_" + std::to_string(shots++);
            const Shot a = shoot(ctx(), smoke.get(), centre, fragment, name + "_fragment.png");
            const Shot b = shoot(ctx(), smoke.get(), centre, compute, name + "_compute.png");
            float largest = 0.0f;
            size_t smoky = 0;
            const Shot plain = shoot(ctx(), nullptr, centre, fragment, "march_plain.png");
            for (size_t i = 0; i < a.linear.size(); ++i) {
                largest = std::max(largest, std::abs(a.linear[i] - b.linear[i]));
                smoky += std::abs(a.linear[i] - plain.linear[i]) > 0.02f ? 1 : 0;
            }
            std::printf("%s: %zu channels with smoke, largest difference %.2e\n", name.c_str(),
                        smoky, double(largest));
            EXPECT_GT(smoky, 500u) << name << ": the smoke shows";
            EXPECT_LE(largest, 2e-3f) << name;
        }
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

// A uniform block of smoke (alpha 0.25, optical density 2 per metre; 0.8 m on a side) alone,
// lit from straight above and seen from the side, 32 m away through a 2.5-degree lens (rays within
// 0.8 degrees of level): per pixel row through the block's middle, from 0.05 m to 0.75 m below its
// top, the red of the full-resolution march and (in `depths`) how far below the top the row's ray
// passes the block's middle plane.
// With `pad`, the block stands in a grid `pad` cells larger on every side, empty there (the same
// smoke in the same place, a pigment box smaller than the grid).
std::vector<float> blockColumn(gpu::Context& ctx, const scene::SmokeShading& shading,
                               std::vector<float>* depths = nullptr, uint32_t maxLightCells = 128,
                               uint32_t pad = 0) {
    fluid::SolverOptions options;
    const uint32_t n = 16 + 2 * pad;
    options.grid = {n, n, n, 0.05f};
    auto block = fluid::SmokeSolver::create(ctx, options).value();
    fluid::FieldState state = fluid::FieldState::zero(options.grid);
    for (uint32_t z = pad; z < pad + 16; ++z)
        for (uint32_t y = pad; y < pad + 16; ++y)
            for (uint32_t x = pad; x < pad + 16; ++x)
                for (uint32_t c = 0; c < 4; ++c)
                    state.pigment[4 * (x + n * (y + n * z)) + c] = 0.25f; // white, alpha 0.25
    block->setState(state);
    const glm::vec3 centre(0.0f, 1.0f, 0.0f);
    scene::Scene s = scene::kickScene();
    s.camera.position = centre + glm::vec3(0.0f, 0.0f, 32.0f);
    s.camera.target = centre;
    s.camera.fovDegrees = 2.5f;
    s.lights[0].direction = glm::vec3(0.0f, -1.0f, 0.0f);
    s.lights[0].intensity = 1.0f;
    const render::SceneCamera camera = render::makeCamera(s.camera, float(kWidth) / kHeight);
    render::RenderTarget target = render::createRenderTarget(ctx, kWidth, kHeight);
    render::SmokePass smokePass(ctx);
    render::SmokeLook look;
    look.resolution = render::SmokeResolution::Full;
    look.maxLightCells = maxLightCells;
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        render::beginRendering(cmd, target, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        render::endRendering(cmd);
        const render::SmokePass::Volume volume{block->pigmentVolume(), options.grid,
                                               centre - glm::vec3(0.4f + 0.05f * float(pad)),
                                               shading};
        smokePass.draw(cmd, target, std::span(&volume, 1), camera, s.lights[0], look);
    });
    const std::vector<float> rgba = render::readLinearColor(ctx, target);
    const glm::mat4 inverse = glm::inverse(camera.viewProjection);
    std::vector<float> column;
    for (uint32_t row = 0; row < kHeight; ++row) {
        // The row's ray through the middle of the picture, where it crosses the plane z = 0.
        const float clipY = 1.0f - 2.0f * (float(row) + 0.5f) / float(kHeight);
        const glm::vec4 far = inverse * glm::vec4(0.0f, clipY, 1.0f, 1.0f);
        const glm::vec3 dir = glm::vec3(far) / far.w - s.camera.position;
        const glm::vec3 mid = s.camera.position + dir * (-s.camera.position.z / dir.z);
        const float d = centre.y + 0.4f - mid.y;
        if (d < 0.05f || d > 0.75f) continue;
        column.push_back(rgba[(size_t(row) * kWidth + kWidth / 2) * 4]);
        if (depths) depths->push_back(d);
    }
    return column;
}

// Single scattering with self-shadowing over the smoke's whole depth: along a level ray through
// the uniform block the light's transmittance is exp(-sigma d) at every sample, d the depth below
// the top, so a row's colour is P + Q exp(-sigma d) (P: the ambient part). Fitted to the rows, the
// sigma that explains them best is the block's own, 2 per metre. A shadow march that stops short
// of the top (the four samples 0.1 m apart this pass once took) leaves the rows below 0.4 m alike,
// and the fit far from it.
struct DecayFit {
    double sigma = 0.0;
    double rms = 0.0;
};

// Least squares of P + Q e^(-sigma d) over sigma in steps of 0.01 (P and Q in closed form).
DecayFit fitDecay(const std::vector<float>& column, const std::vector<float>& depths) {
    DecayFit best{0.0, 1e30};
    for (int step = 50; step <= 800; ++step) {
        const double sigma = 0.01 * step;
        std::vector<double> e(column.size()), v(column.begin(), column.end());
        for (size_t i = 0; i < column.size(); ++i)
            e[i] = std::exp(-sigma * double(depths[i]));
        double me = 0.0, mv = 0.0;
        for (size_t i = 0; i < column.size(); ++i) {
            me += e[i];
            mv += v[i];
        }
        me /= double(column.size());
        mv /= double(column.size());
        double see = 0.0, sev = 0.0;
        for (size_t i = 0; i < column.size(); ++i) {
            see += (e[i] - me) * (e[i] - me);
            sev += (e[i] - me) * (v[i] - mv);
        }
        const double q = sev / see, p = mv - q * me;
        double error = 0.0;
        for (size_t i = 0; i < column.size(); ++i)
            error += (p + q * e[i] - v[i]) * (p + q * e[i] - v[i]);
        const double rms = std::sqrt(error / double(column.size()));
        if (rms < best.rms) best = {sigma, rms};
    }
    return best;
}

TEST_F(SmokePassTest, SelfShadowingReachesThroughTheWholeDepth) {
    std::vector<float> depths;
    const std::vector<float> column = blockColumn(ctx(), {}, &depths);
    ASSERT_GT(column.size(), 40u) << "rows through the block";
    const DecayFit fit = fitDecay(column, depths);
    std::printf("%zu rows, red %.4f at 0.05 m below the top to %.4f at 0.75 m; fitted sigma %.2f "
                "(the block's: 2), rms %.5f\n",
                column.size(), double(column.front()), double(column.back()), fit.sigma, fit.rms);
    for (size_t i = 1; i < column.size(); ++i)
        ASSERT_LE(column[i], column[i - 1] + 1e-3f) << "deeper is darker, at " << depths[i] << " m";
    EXPECT_NEAR(fit.sigma, 2.0, 0.1);
}

// A pigment box wider than the light's transmittance volume (SmokeLook::maxLightCells; a large
// sparse domain's smoke): the 16-cell block's light in 6 texels a side, each spanning 2.7 cells.
// The light still reaches through the whole depth, and the decay still fits the block's sigma,
// coarser: the texels' centres sample exp(-sigma d) 0.13 m apart and the filter joins them by
// straight lines.
TEST_F(SmokePassTest, ABoxWiderThanTheLightVolumeSharesItsTexels) {
    std::vector<float> depths;
    const std::vector<float> column = blockColumn(ctx(), {}, &depths, 6);
    ASSERT_GT(column.size(), 40u) << "rows through the block";
    const DecayFit fit = fitDecay(column, depths);
    std::printf("6 light texels a side: red %.4f at 0.05 m to %.4f at 0.75 m; fitted sigma %.2f, "
                "rms %.5f\n",
                double(column.front()), double(column.back()), fit.sigma, fit.rms);
    for (size_t i = 1; i < column.size(); ++i)
        ASSERT_LE(column[i], column[i - 1] + 1e-3f) << "deeper is darker, at " << depths[i] << " m";
    EXPECT_NEAR(fit.sigma, 2.0, 0.2);
    // It is not the full-resolution picture: the texels are shared.
    const std::vector<float> full = blockColumn(ctx(), {});
    double largest = 0.0;
    for (size_t i = 0; i < full.size() && i < column.size(); ++i)
        largest = std::max(largest, double(std::abs(full[i] - column[i])));
    EXPECT_GT(largest, 1e-4);
}

// The light's volume covers the pigment's box, not the grid: the same block in a grid 8 cells
// larger on every side (its box 18 cells of 32) is lit as in its own grid, where the box is the
// grid; a fetch that took the box for the whole image would light it from the wrong texels.
TEST_F(SmokePassTest, TheLightVolumeFollowsThePigmentsBoxInsideALargerGrid) {
    const std::vector<float> own = blockColumn(ctx(), {});
    const std::vector<float> padded = blockColumn(ctx(), {}, nullptr, 128, 8);
    ASSERT_EQ(own.size(), padded.size());
    double largest = 0.0;
    for (size_t i = 0; i < own.size(); ++i)
        largest = std::max(largest, double(std::abs(own[i] - padded[i])));
    std::printf("%zu rows: largest difference %.5f (red from %.4f to %.4f)\n", own.size(), largest,
                double(own.back()), double(own.front()));
    EXPECT_LT(largest, 0.01);
}

// Cel smoke: with 3 bands the light's transmittance takes the levels k / 3, so down the block the
// rows fall into at most 4 flat tones (rows within 1% of the column's range of each other, 3 rows
// or more), a row or two between them where a ray crosses from one band into the next; smooth
// shading has no such tones.
TEST_F(SmokePassTest, CelSmokeShowsItsBandsAsFlatTones) {
    struct Tones {
        size_t flat = 0;        // tones of 3 rows or more
        float flatShare = 0.0f; // of the rows, those in them
    };
    auto tones = [](const std::vector<float>& column) {
        const auto [low, high] = std::minmax_element(column.begin(), column.end());
        const float tolerance = 0.01f * (*high - *low);
        std::vector<std::pair<float, size_t>> tone; // value, rows
        for (float v : column) {
            auto same = std::find_if(tone.begin(), tone.end(), [&](const auto& t) {
                return std::abs(t.first - v) <= tolerance;
            });
            if (same == tone.end())
                tone.emplace_back(v, 1);
            else
                ++same->second;
        }
        Tones t;
        size_t inFlat = 0;
        for (const auto& [value, rows] : tone)
            if (rows >= 3) {
                ++t.flat;
                inFlat += rows;
            }
        t.flatShare = float(inFlat) / float(column.size());
        return t;
    };
    scene::SmokeShading cel;
    cel.celBands = 3;
    const Tones smooth = tones(blockColumn(ctx(), {})), banded = tones(blockColumn(ctx(), cel));
    std::printf(
        "flat tones down the block: smooth %zu (%.0f%% of the rows), 3 bands %zu (%.0f%%)\n",
        smooth.flat, 100.0 * double(smooth.flatShare), banded.flat,
        100.0 * double(banded.flatShare));
    EXPECT_LT(smooth.flatShare, 0.2f);
    EXPECT_GE(banded.flat, 2u);
    EXPECT_LE(banded.flat, 4u);
    EXPECT_GT(banded.flatShare, 0.9f);
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
