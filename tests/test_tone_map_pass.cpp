// The tone map (render/tone_map_pass.h): black stays black, brighter stays brighter, the ACES fit
// is the published curve, and without a tone map the output is the clamped colour.
#include "core/gpu/commands.h"
#include "render/tone_map_pass.h"
#include "tests/gpu_test.h"
#include "tests/post_test_util.h"

#include <cmath>
#include <limits>

namespace mfx::test {
namespace {

class ToneMapPassTest : public GpuTest {
protected:
    static constexpr uint32_t kWidth = 256, kHeight = 2;

    // The sRGB output (red channel, first row) of a row of linear values 0, ..., `top`, spaced
    // so that every decade has as many pixels.
    static std::vector<uint8_t> mapRamp(const scene::PostSpec& post,
                                        std::vector<float>* values = nullptr) {
        std::vector<float> rgba(size_t(kWidth) * kHeight * 4, 1.0f);
        std::vector<float> ramp(kWidth);
        for (uint32_t x = 0; x < kWidth; ++x) {
            ramp[x] = x == 0 ? 0.0f : 1e-3f * std::pow(10.0f, 4.5f * float(x) / (kWidth - 1));
            for (uint32_t y = 0; y < kHeight; ++y)
                for (int c = 0; c < 3; ++c)
                    rgba[(size_t(y) * kWidth + x) * 4 + c] = ramp[x];
        }
        render::RenderTarget picture = render::createRenderTarget(ctx(), kWidth, kHeight);
        render::RenderTarget output = render::createOutputTarget(ctx(), kWidth, kHeight);
        fillSceneColour(ctx(), picture, rgba);
        render::ToneMapPass pass(ctx());
        gpu::submitOneShot(
            ctx(), [&](VkCommandBuffer cmd) { pass.record(cmd, picture.color, output, post); });
        const std::vector<uint8_t> out = render::readColor(ctx(), output);
        std::vector<uint8_t> red(kWidth);
        for (uint32_t x = 0; x < kWidth; ++x)
            red[x] = out[x * 4];
        if (values) *values = ramp;
        return red;
    }

    static scene::PostSpec aces(float exposure = 0.0f) {
        scene::PostSpec post;
        post.toneMap = scene::ToneMap::Aces;
        post.exposure = exposure;
        return post;
    }
};

TEST_F(ToneMapPassTest, AcesMapsZeroToZeroAndIsMonotonic) {
    std::vector<float> values;
    const std::vector<uint8_t> out = mapRamp(aces(), &values);
    EXPECT_EQ(out.front(), 0);
    EXPECT_EQ(out.back(), 255) << "31.6 is past where the curve reaches 1";
    int rises = 0;
    for (uint32_t x = 1; x < kWidth; ++x) {
        ASSERT_GE(out[x], out[x - 1]) << "at " << values[x];
        rises += out[x] > out[x - 1] ? 1 : 0;
    }
    // The ramp's last 37 values lie past 7.24, where the curve reaches 1, and the toe packs the
    // lowest decade into a few levels: of the other steps, most stay distinct.
    EXPECT_GT(rises, 130);
}

TEST_F(ToneMapPassTest, AcesIsNarkowiczsFit) {
    std::vector<float> values;
    const std::vector<uint8_t> out = mapRamp(aces(), &values);
    int worst = 0;
    for (uint32_t x = 0; x < kWidth; ++x) {
        const float v = values[x];
        const float expected = (v * (2.51f * v + 0.03f)) / (v * (2.43f * v + 0.59f) + 0.14f);
        worst = std::max(worst, std::abs(int(out[x]) - int(render::encodeSrgb8(expected))));
    }
    EXPECT_LE(worst, 1);
}

TEST_F(ToneMapPassTest, WithoutAToneMapTheColourIsClamped) {
    std::vector<float> values;
    scene::PostSpec clamped; // the defaults turn the curve on
    clamped.toneMap = scene::ToneMap::None;
    const std::vector<uint8_t> out = mapRamp(clamped, &values);
    for (uint32_t x = 0; x < kWidth; ++x)
        ASSERT_NEAR(out[x], render::encodeSrgb8(values[x]), 1) << "at " << values[x];
}

TEST_F(ToneMapPassTest, OneStopOfExposureDoublesTheColour) {
    scene::PostSpec brighter;
    brighter.exposure = 1.0f;
    brighter.toneMap = scene::ToneMap::None;
    std::vector<float> values;
    const std::vector<uint8_t> out = mapRamp(brighter, &values);
    for (uint32_t x = 0; x < kWidth; ++x)
        ASSERT_NEAR(out[x], render::encodeSrgb8(2.0f * values[x]), 1) << "at " << values[x];
    // And through the curve: a stop down darkens every lit value.
    const std::vector<uint8_t> normal = mapRamp(aces());
    const std::vector<uint8_t> darker = mapRamp(aces(-1.0f));
    for (uint32_t x = 1; x < kWidth; ++x) {
        if (normal[x] > 0 && normal[x] < 255) {
            ASSERT_LE(darker[x], normal[x]) << "at " << x;
        }
    }
}

TEST_F(ToneMapPassTest, InfinityIsWhiteAndNaNIsBlack) {
    std::vector<float> rgba(size_t(kWidth) * kHeight * 4, 0.5f);
    rgba[0] = rgba[1] = rgba[2] = std::numeric_limits<float>::infinity();
    rgba[4] = rgba[5] = rgba[6] = std::numeric_limits<float>::quiet_NaN();
    render::RenderTarget picture = render::createRenderTarget(ctx(), kWidth, kHeight);
    render::RenderTarget output = render::createOutputTarget(ctx(), kWidth, kHeight);
    fillSceneColour(ctx(), picture, rgba);
    render::ToneMapPass pass(ctx());
    gpu::submitOneShot(
        ctx(), [&](VkCommandBuffer cmd) { pass.record(cmd, picture.color, output, aces()); });
    const std::vector<uint8_t> out = render::readColor(ctx(), output);
    EXPECT_EQ(out[0], 255);
    EXPECT_EQ(out[4], 0);
}

} // namespace
} // namespace mfx::test
