// The viewer's status text (render/text_overlay.h): lit pixels only inside the text's box, every
// glyph drawn, scale multiplying the lit area, unknown characters blank, clipping at the edge.
#include "gpu_test.h"

#include "core/gpu/commands.h"
#include "render/render_target.h"
#include "render/text_overlay.h"

#include <string>

namespace mfx::test {
namespace {

class TextOverlay : public GpuTest {
protected:
    static constexpr uint32_t kWidth = 96, kHeight = 32;

    // The target after drawing `text` in white over a red box at `origin`; the clear is blue.
    std::vector<uint8_t> draw(const std::string& text, glm::ivec2 origin, uint32_t scale) {
        render::RenderTarget target = render::createRenderTarget(ctx(), kWidth, kHeight);
        gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
            render::beginRendering(cmd, target, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
            render::drawText(cmd, text, origin, scale, glm::vec4(1.0f),
                             glm::vec4(1.0f, 0.0f, 0.0f, 1.0f), {kWidth, kHeight});
            render::endRendering(cmd);
        });
        return render::readColor(ctx(), target);
    }
    struct Count {
        size_t white = 0, red = 0, whiteOutsideBox = 0;
    };
    static Count count(const std::vector<uint8_t>& rgba, glm::ivec2 lo, glm::ivec2 hi) {
        Count c;
        for (uint32_t y = 0; y < kHeight; ++y)
            for (uint32_t x = 0; x < kWidth; ++x) {
                const uint8_t* p = &rgba[(size_t(y) * kWidth + x) * 4];
                const bool white = p[0] == 255 && p[1] == 255 && p[2] == 255;
                c.white += white;
                c.red += p[0] == 255 && p[1] == 0 && p[2] == 0;
                const bool inside =
                    int(x) >= lo.x && int(x) < hi.x && int(y) >= lo.y && int(y) < hi.y;
                c.whiteOutsideBox += white && !inside;
            }
        return c;
    }
};

TEST_F(TextOverlay, GlyphsLieInsideTheirBoxOnABackground) {
    const glm::ivec2 origin(4, 4);
    const glm::uvec2 size = render::textSize("FRAME 12/27", 1);
    EXPECT_EQ(size, glm::uvec2(11 * 6 - 1, 7));
    const Count c = count(draw("FRAME 12/27", origin, 1), origin, origin + glm::ivec2(size));
    EXPECT_GT(c.white, 60u);
    EXPECT_EQ(c.whiteOutsideBox, 0u);
    // The box: the text's area plus one pixel around, less the lit pixels.
    EXPECT_EQ(c.red + c.white, size_t(size.x + 2) * (size.y + 2));
}

TEST_F(TextOverlay, EveryGlyphLightsPixelsAndUnknownOnesStayBlank) {
    const std::string all = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ.,:/-+=()[]%<>";
    for (char ch : all) {
        const Count c = count(draw(std::string(1, ch), {2, 2}, 1), {2, 2}, {7, 9});
        EXPECT_GT(c.white, 1u) << "'" << ch << "' drew nothing";
        EXPECT_EQ(c.whiteOutsideBox, 0u) << ch;
    }
    EXPECT_EQ(count(draw("~", {2, 2}, 1), {2, 2}, {7, 9}).white, 0u);
    // Lower case is drawn as capitals.
    EXPECT_EQ(draw("ms", {2, 2}, 1), draw("MS", {2, 2}, 1));
}

TEST_F(TextOverlay, ScaleMultipliesTheLitArea) {
    const size_t one = count(draw("24 FPS", {1, 1}, 1), {0, 0}, {int(kWidth), int(kHeight)}).white;
    const size_t two = count(draw("24 FPS", {1, 1}, 2), {0, 0}, {int(kWidth), int(kHeight)}).white;
    EXPECT_EQ(two, 4 * one);
}

TEST_F(TextOverlay, TextPastTheEdgeIsClipped) {
    // Starting left of and above the target, and running off its right edge: no error from the
    // validation layer (the fixture checks), and only what is inside is drawn.
    const Count c = count(draw("CLIPPED TEXT RUNS OFF THE EDGE", {-7, -3}, 2), {-7, -3},
                          {int(kWidth), int(kHeight)});
    EXPECT_GT(c.white, 0u);
    EXPECT_EQ(c.whiteOutsideBox, 0u);
}

} // namespace
} // namespace mfx::test
