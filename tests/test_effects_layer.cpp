// The effects layer (render/effects_layer.h): laid over the frame without effects it gives the
// full frame back, it is a valid premultiplied image, and it is transparent where the effects
// change nothing; and `motionfx render --layers` writes it for every frame.
#include "render/effects_layer.h"
#include "render/image_output.h"
#include "tests/cli_run.h"

#include <filesystem>
#include <gtest/gtest.h>
#include <random>

namespace mfx::test {
namespace {

// Mean absolute difference over the RGB channels, in 8-bit levels.
double meanDifference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < a.size(); ++i)
        if (i % 4 != 3) {
            sum += std::abs(int(a[i]) - int(b[i]));
            ++n;
        }
    return sum / double(n);
}

TEST(EffectsLayer, OverTheFrameWithoutEffectsItGivesTheFullFrame) {
    // Every kind of change: brighter, darker, mixed channels, unchanged, black and white.
    std::mt19937 random(3);
    std::vector<uint8_t> full(4 * 4096), under(4 * 4096);
    for (size_t p = 0; p < full.size(); ++p) {
        under[p] = uint8_t(random() % 256);
        full[p] = p % 3 == 0 ? under[p] : uint8_t(random() % 256);
    }
    const std::vector<uint8_t> layer = render::effectsLayer(full, under);
    const std::vector<uint8_t> composite = render::compositeOver(layer, under);
    int worst = 0;
    for (size_t i = 0; i < full.size(); ++i)
        if (i % 4 != 3) worst = std::max(worst, std::abs(int(composite[i]) - int(full[i])));
    EXPECT_LE(worst, 1);
    EXPECT_LT(meanDifference(composite, full), 0.5);
    for (size_t p = 0; p < layer.size(); p += 4)
        for (int c = 0; c < 3; ++c)
            ASSERT_LE(layer[p + c], layer[p + 3]) << "premultiplied: colour within alpha";
}

TEST(EffectsLayer, TransparentWhereNothingChanges) {
    const std::vector<uint8_t> frame = {10, 20, 30, 255, 200, 100, 0, 255};
    const std::vector<uint8_t> layer = render::effectsLayer(frame, frame);
    EXPECT_EQ(layer, std::vector<uint8_t>(8, 0));
}

TEST(EffectsLayer, AWhiteEffectOverBlackIsOpaqueWhite) {
    const std::vector<uint8_t> white = {255, 255, 255, 255}, black = {0, 0, 0, 255};
    const std::vector<uint8_t> layer = render::effectsLayer(white, black);
    EXPECT_EQ(layer, (std::vector<uint8_t>{255, 255, 255, 255}));
}

// The whole scene (every effect kind, smoke and bloom-free defaults) through the program.
TEST(Cli, RenderLayersCompositeToTheFullFrame) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/cli_render_layers";
    std::filesystem::remove_all(dir);
    const RunResult r = runMotionfx("render \"" + std::string(MFX_SOURCE_DIR) +
                                    "/docs/scenes/all.json\" --size 96x54 --frames 14 --layers "
                                    "--out " +
                                    dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (uint32_t frame : {6u, 13u}) {
        char suffix[16];
        std::snprintf(suffix, sizeof suffix, "_%04u.png", frame);
        auto read = [&](const char* prefix) {
            Result<render::RgbaImage> image = render::readPng(dir + "/" + prefix + suffix);
            EXPECT_TRUE(image) << (image ? "" : image.error().message);
            return image ? image.value().rgba : std::vector<uint8_t>{};
        };
        const std::vector<uint8_t> full = read("frame"), under = read("character"),
                                   layer = read("effects");
        ASSERT_EQ(full.size(), 96u * 54u * 4u);
        ASSERT_EQ(under.size(), full.size());
        ASSERT_EQ(layer.size(), full.size());
        const double error = meanDifference(render::compositeOver(layer, under), full);
        size_t covered = 0, clear = 0;
        for (size_t p = 3; p < layer.size(); p += 4) {
            covered += layer[p] > 0 ? 1 : 0;
            clear += layer[p] == 0 ? 1 : 0;
        }
        std::cout << "frame " << frame << ": composite mean error " << error << " of 255; layer "
                  << covered << " pixels with alpha, " << clear << " clear\n";
        EXPECT_LE(error, 1.0) << "frame " << frame;
        EXPECT_GT(covered, 100u) << "the effects are in the layer";
        EXPECT_GT(clear, 1000u) << "and only the effects";
        EXPECT_NE(full, under) << "the effects change the frame";
    }
}

} // namespace
} // namespace mfx::test
