// The bloom (render/bloom_pass.h): it moves light without adding or removing it, and a brighter
// point glows further.
#include "core/gpu/commands.h"
#include "render/bloom_pass.h"
#include "tests/gpu_test.h"
#include "tests/post_test_util.h"
#include "tests/scene_render_util.h"

#include <cmath>
#include <limits>
#include <random>

namespace mfx::test {
namespace {

class BloomPassTest : public GpuTest {
protected:
    static constexpr uint32_t kWidth = 160, kHeight = 96;

    // `rgba` bloomed with `strength`, read back as linear floats.
    static std::vector<float> bloom(const std::vector<float>& rgba, float strength) {
        render::RenderTarget target = render::createRenderTarget(ctx(), kWidth, kHeight);
        fillSceneColour(ctx(), target, rgba);
        render::BloomPass pass(ctx());
        gpu::submitOneShot(ctx(),
                           [&](VkCommandBuffer cmd) { pass.record(cmd, target.color, strength); });
        return render::readLinearColor(ctx(), target);
    }

    static std::vector<float> black() {
        std::vector<float> rgba(size_t(kWidth) * kHeight * 4, 0.0f);
        for (size_t p = 3; p < rgba.size(); p += 4)
            rgba[p] = 1.0f;
        return rgba;
    }
    static size_t at(uint32_t x, uint32_t y) { return (size_t(y) * kWidth + x) * 4; }

    // The red channel summed over the picture.
    static double totalRed(const std::vector<float>& rgba) {
        double sum = 0.0;
        for (size_t p = 0; p < rgba.size(); p += 4)
            sum += double(rgba[p]);
        return sum;
    }

    // The farthest distance in pixels from (cx, cy) where red exceeds `threshold`.
    static double reach(const std::vector<float>& rgba, uint32_t cx, uint32_t cy, float threshold) {
        double far = 0.0;
        for (uint32_t y = 0; y < kHeight; ++y)
            for (uint32_t x = 0; x < kWidth; ++x)
                if (rgba[at(x, y)] > threshold)
                    far = std::max(far, std::hypot(double(x) - cx, double(y) - cy));
        return far;
    }
};

TEST_F(BloomPassTest, APointKeepsItsEnergy) {
    for (float strength : {0.25f, 1.0f}) {
        std::vector<float> rgba = black();
        rgba[at(80, 48)] = 50.0f;
        const std::vector<float> out = bloom(rgba, strength);
        const double total = totalRed(out);
        std::cout << "strength " << strength << ": total " << total << " of 50, the point keeps "
                  << out[at(80, 48)] << "\n";
        EXPECT_NEAR(total, 50.0, 50.0 * 0.03) << "strength " << strength;
        EXPECT_LT(out[at(80, 48)], 50.0f * (1.0f - strength) + 1.0f) << "the point spreads";
        EXPECT_GT(out[at(80, 60)], 0.0f) << "light 12 pixels away";
    }
}

TEST_F(BloomPassTest, AWholePictureKeepsItsEnergy) {
    // Smooth shading, noise and bright spots, up to the edges.
    std::mt19937 random(7);
    std::uniform_real_distribution<float> noise(0.0f, 0.2f);
    std::vector<float> rgba = black();
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x)
            rgba[at(x, y)] = 0.3f + 0.5f * float(x) / kWidth + noise(random);
    for (int spot = 0; spot < 12; ++spot)
        rgba[at(random() % kWidth, random() % kHeight)] = 20.0f;
    const double before = totalRed(rgba);
    const double after = totalRed(bloom(rgba, 0.5f));
    std::cout << "total before " << before << ", after " << after << " ("
              << 100.0 * (after / before - 1.0) << "%)\n";
    EXPECT_NEAR(after / before, 1.0, 0.03);
}

// A drawn frame (the speed-lines scene's last) with and without bloom: the same light in total,
// a different picture.
TEST_F(BloomPassTest, ADrawnFrameKeepsItsEnergy) {
    auto frame = [](float bloom, std::vector<uint8_t>& output) {
        Result<scene::Scene> s = docScene("lines");
        EXPECT_TRUE(s) << (s ? "" : s.error().message);
        s.value().post.bloom = bloom;
        Result<DrawnScene> drawn = drawScene(ctx(), s.value(), 160, 90);
        EXPECT_TRUE(drawn) << (drawn ? "" : drawn.error().message);
        drawn.value().playTo(ctx());
        output = render::readColor(ctx(), drawn.value().renderer->output());
        const std::vector<float> rgba =
            render::readLinearColor(ctx(), drawn.value().renderer->sceneTarget());
        double sum = 0.0;
        for (size_t i = 0; i < rgba.size(); ++i)
            sum += i % 4 == 3 ? 0.0 : double(rgba[i]);
        return sum;
    };
    std::vector<uint8_t> plain, bloomed;
    const double before = frame(0.0f, plain);
    const double after = frame(0.5f, bloomed);
    std::cout << "linear total without bloom " << before << ", with " << after << "\n";
    EXPECT_NEAR(after / before, 1.0, 0.03);
    EXPECT_NE(plain, bloomed);
}

// Stacked additive light can overflow fp16 to infinity, and a NaN would spread to every texel the
// bloom touches: both stay contained, and the picture stays finite.
TEST_F(BloomPassTest, InfinityAndNaNStayContained) {
    std::vector<float> rgba = black();
    rgba[at(40, 48)] = std::numeric_limits<float>::infinity();
    rgba[at(120, 48)] = std::numeric_limits<float>::quiet_NaN();
    const std::vector<float> out = bloom(rgba, 0.5f);
    size_t bad = 0;
    for (size_t p = 0; p < out.size(); p += 4)
        bad += std::isfinite(out[p]) ? 0 : 1;
    EXPECT_EQ(bad, 0u);
    EXPECT_LT(out[at(140, 48)], 1.0f) << "the NaN spreads no light";
}

TEST_F(BloomPassTest, AnEvenPictureStaysEven) {
    std::vector<float> rgba = black();
    for (size_t p = 0; p < rgba.size(); p += 4)
        rgba[p] = 0.7f;
    const std::vector<float> out = bloom(rgba, 1.0f);
    for (size_t p = 0; p < out.size(); p += 4)
        ASSERT_NEAR(out[p], 0.7f, 0.7f * 2e-3f) << "pixel " << p / 4;
}

TEST_F(BloomPassTest, ABrighterPointGlowsFurther) {
    double last = 0.0;
    for (float intensity : {10.0f, 100.0f, 1000.0f}) {
        std::vector<float> rgba = black();
        rgba[at(80, 48)] = intensity;
        const double radius = reach(bloom(rgba, 0.2f), 80, 48, 0.004f);
        std::cout << "intensity " << intensity << ": above 0.004 out to " << radius << " pixels\n";
        EXPECT_GT(radius, last + 2.0) << "intensity " << intensity;
        last = radius;
    }
}

TEST_F(BloomPassTest, LevelsHalveUntilEightTexels) {
    EXPECT_EQ(render::BloomPass::levelCount(960, 540), 7u); // 480x270 ... 8x5
    EXPECT_EQ(render::BloomPass::levelCount(160, 90), 4u);  // 80x45, 40x23, 20x12, 10x6
    EXPECT_EQ(render::BloomPass::levelCount(16, 16), 2u);
    EXPECT_EQ(render::BloomPass::levelCount(4, 4), 1u);
}

} // namespace
} // namespace mfx::test
