// The GLSL flipbook player (shaders/render/flipbook_player.frag through render/flipbook_player.h)
// against its CPU twin, render/flipbook.h's blendCells, on a sheet whose motion is known: a disc
// crossing four cells, its motion vectors measured by the optical flow and stored in 8 bits.
#include "render/flipbook_player.h"

#include "core/gpu/commands.h"
#include "render/flipbook.h"
#include "render/optical_flow.h"
#include "tests/flipbook_test_util.h"
#include "tests/gpu_test.h"

#include <cmath>

namespace mfx::render {
namespace {

class FlipbookPlayerTest : public test::GpuTest {
protected:
    static constexpr uint32_t kCell = 32;
    FlipbookLayout layout{2, 2, kCell, kCell};

    gpu::Image upload(const std::vector<uint8_t>& rgba) {
        gpu::ImageDesc desc;
        desc.extent = {layout.sheetWidth(), layout.sheetHeight(), 1};
        desc.format = VK_FORMAT_R8G8B8A8_UNORM;
        desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        gpu::Image image = gpu::createImage(ctx(), desc);
        gpu::uploadImage(ctx(), image, std::as_bytes(std::span(rgba)),
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        return image;
    }
};

// Cell values as the sheet stores them (8 bits), read back as the player reads them.
std::vector<uint8_t> quantise(const CellImage& cell) {
    std::vector<uint8_t> rgba(cell.rgba.size());
    for (size_t k = 0; k < rgba.size(); ++k)
        rgba[k] = uint8_t(std::lround(std::clamp(cell.rgba[k], 0.0f, 1.0f) * 255.0f));
    return rgba;
}

TEST_F(FlipbookPlayerTest, PlaysTheSheetAsTheCpuBlendDoes) {
    std::vector<uint8_t> colourSheet(size_t(layout.sheetWidth()) * layout.sheetHeight() * 4);
    std::vector<CellImage> cells;
    for (uint32_t i = 0; i < 4; ++i) {
        const std::vector<uint8_t> cell = quantise(test::disc(kCell, 9.0f + 4.0f * i, 16.0f, 6.0f));
        placeCell(colourSheet, layout, i, cell);
        cells.push_back(cellFromRgba8(cell, kCell, kCell));
    }
    std::vector<MotionField> flows;
    for (uint32_t i = 0; i < 4; ++i)
        flows.push_back(opticalFlow(cells[i], cells[(i + 1) % 4]));
    const float scale = motionScale(flows);
    std::vector<uint8_t> motionSheet(colourSheet.size());
    std::vector<MotionField> stored;
    for (uint32_t i = 0; i < 4; ++i) {
        const std::vector<uint8_t> encoded = encodeMotion(flows[i], scale);
        placeCell(motionSheet, layout, i, encoded);
        stored.push_back(decodeMotion(encoded, kCell, kCell, scale));
    }
    gpu::Image colour = upload(colourSheet);
    gpu::Image motion = upload(motionSheet);
    RenderTarget target = createRenderTarget(ctx(), kCell, kCell);
    FlipbookPlayer player(ctx());

    struct Case {
        float position;
        bool loop, withMotion;
        uint32_t a, b;
        float t;
    };
    const Case cases[] = {{0.0f, false, true, 0, 1, 0.0f},  {0.25f, false, true, 0, 1, 0.25f},
                          {1.5f, false, true, 1, 2, 0.5f},  {2.75f, false, true, 2, 3, 0.75f},
                          {3.5f, true, true, 3, 0, 0.5f},   {7.25f, true, true, 3, 0, 0.25f},
                          {1.5f, false, false, 1, 2, 0.5f}, {3.5f, false, true, 3, 3, 0.0f}};
    for (const Case& c : cases) {
        shared::FlipbookPlay play{};
        play.grid = glm::vec4(2.0f, 2.0f, 4.0f, c.withMotion ? scale : 0.0f);
        play.playhead = glm::vec4(c.position, c.loop ? 1.0f : 0.0f, 0.0f, 0.0f);
        play.quad = glm::vec4(-1.0f, -1.0f, 1.0f, 1.0f);
        gpu::submitOneShot(
            ctx(), [&](VkCommandBuffer cmd) { player.record(cmd, target, colour, motion, play); });
        const std::vector<float> gpu = readLinearColor(ctx(), target);
        const CellImage cpu =
            blendCells(cells[c.a], cells[c.b], c.withMotion ? &stored[c.a] : nullptr, c.t);
        float largest = 0.0f;
        for (size_t k = 0; k < gpu.size(); ++k)
            largest = std::max(largest, std::abs(gpu[k] - cpu.rgba[k]));
        // The target is fp16: half a unit in the last place of values up to 1 is 2.4e-4.
        EXPECT_LT(largest, 1e-3f) << "position " << c.position << (c.loop ? " looped" : "");
    }
}

TEST_F(FlipbookPlayerTest, TheMotionMovesTheDiscRatherThanFadingIt) {
    // Halfway between two cells the played disc's centre of coverage is halfway between theirs.
    std::vector<uint8_t> colourSheet(size_t(layout.sheetWidth()) * layout.sheetHeight() * 4);
    std::vector<CellImage> cells;
    for (uint32_t i = 0; i < 2; ++i) {
        const std::vector<uint8_t> cell =
            quantise(test::disc(kCell, 10.0f + 10.0f * i, 16.0f, 6.0f));
        placeCell(colourSheet, layout, i, cell);
        cells.push_back(cellFromRgba8(cell, kCell, kCell));
    }
    const MotionField flow = opticalFlow(cells[0], cells[1]);
    const float scale = motionScale(std::span(&flow, 1));
    std::vector<uint8_t> motionSheet(colourSheet.size());
    placeCell(motionSheet, layout, 0, encodeMotion(flow, scale));
    gpu::Image colour = upload(colourSheet);
    gpu::Image motion = upload(motionSheet);
    RenderTarget target = createRenderTarget(ctx(), kCell, kCell);
    FlipbookPlayer player(ctx());
    shared::FlipbookPlay play{};
    play.grid = glm::vec4(2.0f, 2.0f, 2.0f, scale);
    play.playhead = glm::vec4(0.5f, 0.0f, 0.0f, 0.0f);
    play.quad = glm::vec4(-1.0f, -1.0f, 1.0f, 1.0f);
    gpu::submitOneShot(
        ctx(), [&](VkCommandBuffer cmd) { player.record(cmd, target, colour, motion, play); });
    const std::vector<float> picture = readLinearColor(ctx(), target);
    double sum = 0.0, weighted = 0.0, peak = 0.0;
    for (uint32_t y = 0; y < kCell; ++y)
        for (uint32_t x = 0; x < kCell; ++x) {
            const float a = picture[(size_t(y) * kCell + x) * 4 + 3];
            sum += a;
            weighted += a * (x + 0.5);
            peak = std::max(peak, double(a));
        }
    EXPECT_NEAR(weighted / sum, 15.0, 0.5);
    // A cross-fade would leave two half-covered discs; the moved one is whole.
    EXPECT_GT(peak, 0.9);
}

} // namespace
} // namespace mfx::render
