// Golden-image tests: the scenes of docs/scenes/ (the character alone, each effect alone, and
// all together) rendered at 160x90 to their 21st frame and compared with tests/golden/NAME.png,
// images made by `motionfx render docs/scenes/NAME.json --size 160x90` (tests/golden/update.sh)
// and reviewed by eye. On failure the test writes the image it made, the expected one and a diff
// side by side into tests/output/golden/.
#include "gpu_test.h"

#include "core/gpu/commands.h"
#include "core/scene/scene.h"
#include "render/frame_renderer.h"
#include "render/image_output.h"
#include "sim/scene_simulation.h"
#include "tests/scene_render_util.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>

namespace mfx::test {
namespace {

constexpr uint32_t kWidth = 160, kHeight = 90;

// Tolerance. The same device and driver give the same bytes; lavapipe on another CPU (another
// vector width, fused multiply-adds or not) may move an edge pixel's coverage by a sample or two
// and the smoke's density by a little, so a few pixels may differ by a visible step and the whole
// image on average by a fraction of one level. Both bounds stay far below what removing any one
// effect changes (GoldenImage.ToleranceSeesEachEffect).
constexpr int kPixelThreshold = 16;         // of 255, on the largest channel difference
constexpr double kMaxPixelsOver = 0.0025;   // fraction of pixels beyond kPixelThreshold
constexpr double kMaxMeanDifference = 0.25; // of 255, mean over every channel of every pixel

struct Difference {
    double meanAbs = 0.0;      // of 255
    double fractionOver = 0.0; // pixels with a channel beyond kPixelThreshold
    int largest = 0;
    bool withinTolerance() const {
        return fractionOver <= kMaxPixelsOver && meanAbs <= kMaxMeanDifference;
    }
};

Difference compare(const render::RgbaImage& a, const render::RgbaImage& b) {
    Difference d;
    size_t over = 0, sum = 0;
    const size_t pixels = size_t(a.width) * a.height;
    for (size_t p = 0; p < pixels; ++p) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            const int diff = std::abs(int(a.rgba[p * 4 + c]) - int(b.rgba[p * 4 + c]));
            sum += size_t(diff);
            worst = std::max(worst, diff);
        }
        over += worst > kPixelThreshold ? 1 : 0;
        d.largest = std::max(d.largest, worst);
    }
    d.meanAbs = double(sum) / double(pixels * 3);
    d.fractionOver = double(over) / double(pixels);
    return d;
}

// Made, expected and their difference side by side: the difference is 4x amplified grey, red where
// a pixel is beyond the threshold.
render::RgbaImage sideBySide(const render::RgbaImage& made, const render::RgbaImage& expected) {
    const uint32_t w = made.width, h = made.height;
    render::RgbaImage out{w * 3, h, std::vector<uint8_t>(size_t(w) * 3 * h * 4, 255)};
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const size_t p = (size_t(y) * w + x) * 4;
            int worst = 0;
            for (int c = 0; c < 3; ++c)
                worst =
                    std::max(worst, std::abs(int(made.rgba[p + c]) - int(expected.rgba[p + c])));
            const uint8_t grey = uint8_t(std::min(255, worst * 4));
            const uint8_t diff[4] = {worst > kPixelThreshold ? uint8_t(255) : grey,
                                     worst > kPixelThreshold ? uint8_t(0) : grey,
                                     worst > kPixelThreshold ? uint8_t(0) : grey, 255};
            const uint8_t* sources[3] = {&made.rgba[p], &expected.rgba[p], diff};
            for (int panel = 0; panel < 3; ++panel)
                std::copy_n(sources[panel], 4,
                            &out.rgba[(size_t(y) * out.width + size_t(panel) * w + x) * 4]);
        }
    return out;
}

class GoldenImage : public GpuTest {
protected:
    // The last frame of docs/scenes/NAME.json, rendered as `motionfx render --size 160x90` does.
    // With `restartAfter` > 0 the renderer first draws that many frames of another simulation of
    // the scene, which is destroyed before the one drawn (as a restarted view does). Without
    // `effects` the scene's effects are left out (the character alone, in the scene's shot).
    static render::RgbaImage renderScene(const std::string& name, uint32_t restartAfter = 0,
                                         bool effects = true) {
        Result<scene::Scene> loaded = docScene(name);
        EXPECT_TRUE(loaded) << (loaded ? "" : loaded.error().message);
        if (!loaded) return {};
        scene::Scene s = std::move(loaded).value();
        s.output.width = kWidth;
        s.output.height = kHeight;
        if (!effects) s.effects.clear();
        Result<DrawnScene> drawn = drawScene(ctx(), s, kWidth, kHeight);
        EXPECT_TRUE(drawn) << (drawn ? "" : drawn.error().message);
        if (!drawn) return {};
        DrawnScene& d = drawn.value();
        if (restartAfter > 0) {
            playFrames(ctx(), *d.renderer, *d.simulation, 0,
                       std::min(restartAfter, d.simulation->frameCount()));
            d.simulation.reset();
            auto again = sim::SceneSimulation::create(ctx(), s, *d.cast);
            EXPECT_TRUE(again) << (again ? "" : again.error().message);
            if (!again) return {};
            d.simulation = std::move(again).value();
        }
        d.playTo(ctx());
        return {kWidth, kHeight, render::readColor(ctx(), d.renderer->output())};
    }

    static render::RgbaImage expected(const std::string& name) {
        Result<render::RgbaImage> read =
            render::readPng(std::string(MFX_SOURCE_DIR) + "/tests/golden/" + name + ".png");
        EXPECT_TRUE(read) << (read ? "" : read.error().message);
        return read ? std::move(read).value() : render::RgbaImage{};
    }

    static void checkGolden(const std::string& name, uint32_t restartAfter = 0) {
        const render::RgbaImage made = renderScene(name, restartAfter);
        const render::RgbaImage golden = expected(name);
        ASSERT_EQ(made.rgba.size(), size_t(kWidth) * kHeight * 4);
        ASSERT_EQ(golden.width, kWidth);
        ASSERT_EQ(golden.height, kHeight);
        const Difference d = compare(made, golden);
        if (!d.withinTolerance()) {
            const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/golden";
            ASSERT_TRUE(render::ensureOutputDirectory(dir));
            const render::RgbaImage panel = sideBySide(made, golden);
            EXPECT_TRUE(render::writePng(dir + "/" + name + ".png", kWidth, kHeight, made.rgba));
            EXPECT_TRUE(
                render::writePng(dir + "/" + name + ".expected.png", kWidth, kHeight, golden.rgba));
            EXPECT_TRUE(render::writePng(dir + "/" + name + ".diff.png", panel.width, panel.height,
                                         panel.rgba));
            ADD_FAILURE() << name << ": " << d.fractionOver * 100.0 << "% of pixels differ by more "
                          << "than " << kPixelThreshold << " (at most " << kMaxPixelsOver * 100.0
                          << "%), mean difference " << d.meanAbs << " (at most "
                          << kMaxMeanDifference << "), largest " << d.largest
                          << "; made, expected and diff (made | expected | difference) in " << dir;
        }
    }
};

TEST_F(GoldenImage, CharacterAlone) {
    checkGolden("none");
}
TEST_F(GoldenImage, SpeedLines) {
    checkGolden("lines");
}
TEST_F(GoldenImage, MotionBlur) {
    checkGolden("blur");
}
TEST_F(GoldenImage, MotionParticles) {
    checkGolden("particles");
}
TEST_F(GoldenImage, Smoke) {
    checkGolden("smoke");
}
TEST_F(GoldenImage, AllEffects) {
    checkGolden("all");
}
TEST_F(GoldenImage, AfterimageSmear) {
    checkGolden("afterimage");
}
TEST_F(GoldenImage, SweptVolume) {
    checkGolden("swept");
}
TEST_F(GoldenImage, SilhouetteShell) {
    checkGolden("shell");
}

// A renderer outlives the simulation it was made for: after drawing a few frames of one that is
// then destroyed, it draws a new simulation of the scene as a fresh renderer would (the view's
// restart; it once kept the destroyed simulation's scene and smoke descriptor sets).
TEST_F(GoldenImage, RendererDrawsARestartedSimulation) {
    checkGolden("all", 5);
}

// The tolerance is tight enough to see any one effect: each effect's golden is outside it of the
// character alone, and the combined shot is outside it of each effect alone.
TEST_F(GoldenImage, ToleranceSeesEachEffect) {
    const render::RgbaImage alone = expected("none");
    const render::RgbaImage all = expected("all");
    for (const char* name : {"lines", "blur", "particles", "smoke"}) {
        const render::RgbaImage effect = expected(name);
        ASSERT_EQ(effect.rgba.size(), alone.rgba.size());
        const Difference fromAlone = compare(effect, alone);
        EXPECT_FALSE(fromAlone.withinTolerance())
            << name << " vs the character alone: " << fromAlone.fractionOver * 100.0
            << "% pixels over, mean " << fromAlone.meanAbs;
        if (std::string(name) != "particles") { // the combined shot has no particles
            const Difference fromAll = compare(effect, all);
            EXPECT_FALSE(fromAll.withinTolerance()) << name << " vs all";
        }
    }
}

// The mesh effects' scenes have their own shots: each golden is outside the tolerance of the same
// shot with the effect left out.
TEST_F(GoldenImage, ToleranceSeesEachMeshEffect) {
    for (const char* name : {"afterimage", "swept", "shell"}) {
        const render::RgbaImage alone = renderScene(name, 0, false);
        const render::RgbaImage effect = expected(name);
        ASSERT_EQ(effect.rgba.size(), alone.rgba.size()) << name;
        const Difference d = compare(effect, alone);
        EXPECT_FALSE(d.withinTolerance())
            << name << " vs its shot without the effect: " << d.fractionOver * 100.0
            << "% pixels over, mean " << d.meanAbs;
        std::cout << name << " vs its shot without the effect: " << d.fractionOver * 100.0
                  << "% of pixels over " << kPixelThreshold << ", mean " << d.meanAbs << "\n";
    }
}

} // namespace
} // namespace mfx::test
