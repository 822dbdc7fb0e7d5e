// Flipbooks without a GPU (render/flipbook.h, render/optical_flow.h): the layout's options, the
// frames sampled into cells, the loop's cross-fade, the sheets' encodings, the optical flow on
// pictures whose motion is known, and the player's blend against a plain cross-fade.
#include "render/exr_output.h"
#include "render/flipbook.h"
#include "render/optical_flow.h"
#include "render/six_way.h"
#include "render/smoke_motion.h"
#include "tests/flipbook_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/packing.hpp>

namespace mfx::render {
namespace {

TEST(FlipbookLayout, GridAndCellAreParsed) {
    FlipbookLayout layout;
    ASSERT_TRUE(parseFlipbookGrid("8x4", layout));
    ASSERT_TRUE(parseFlipbookCell("256x128", kMaxSheetSide, layout));
    EXPECT_EQ(layout.columns, 8u);
    EXPECT_EQ(layout.rows, 4u);
    EXPECT_EQ(layout.cells(), 32u);
    EXPECT_EQ(layout.sheetWidth(), 2048u);
    EXPECT_EQ(layout.sheetHeight(), 512u);
    ASSERT_TRUE(parseFlipbookCell("64", kMaxSheetSide, layout));
    EXPECT_EQ(layout.cellWidth, 64u);
    EXPECT_EQ(layout.cellHeight, 64u);
}

TEST(FlipbookLayout, BadGridsAreRefusedInOneLineNamingTheOption) {
    for (const char* text : {"8", "8by8", "x8", "8x", "0x8", "8x0", "65x1", "-1x8", "8x8x8", ""}) {
        FlipbookLayout layout;
        const Status s = parseFlipbookGrid(text, layout);
        ASSERT_FALSE(s) << text;
        EXPECT_EQ(s.error().message.rfind("--grid", 0), 0u) << s.error().message;
        EXPECT_EQ(s.error().message.find('\n'), std::string::npos);
    }
}

TEST(FlipbookLayout, BadCellsAreRefusedInOneLineNamingTheOption) {
    for (const char* text : {"0", "4", "256x4", "abc", "256x", "2049", "99999999999"}) {
        FlipbookLayout layout; // 8x8: at most 2048 a side
        const Status s = parseFlipbookCell(text, kMaxSheetSide, layout);
        ASSERT_FALSE(s) << text;
        EXPECT_EQ(s.error().message.rfind("--cell", 0), 0u) << s.error().message;
        EXPECT_EQ(s.error().message.find('\n'), std::string::npos);
    }
    FlipbookLayout wide;
    ASSERT_TRUE(parseFlipbookGrid("16x1", wide));
    EXPECT_FALSE(parseFlipbookCell("1025x1025", kMaxSheetSide, wide));
    EXPECT_TRUE(parseFlipbookCell("1024x4096", kMaxSheetSide, wide)); // 16384 x 4096
    FlipbookLayout big;
    ASSERT_TRUE(parseFlipbookGrid("64x64", big));
    const Status tooMany = parseFlipbookCell("256", kMaxSheetSide, big); // 16384 x 16384
    ASSERT_FALSE(tooMany);
    EXPECT_NE(tooMany.error().message.find("16384x16384"), std::string::npos);
}

TEST(FlipbookFrames, SampledEvenlyWithBothEnds) {
    const Result<std::vector<uint32_t>> five = sampleFrames(10, 18, 5);
    ASSERT_TRUE(five);
    EXPECT_EQ(five.value(), (std::vector<uint32_t>{10, 12, 14, 16, 18}));
    const Result<std::vector<uint32_t>> all = sampleFrames(0, 3, 4);
    ASSERT_TRUE(all);
    EXPECT_EQ(all.value(), (std::vector<uint32_t>{0, 1, 2, 3}));
    const Result<std::vector<uint32_t>> one = sampleFrames(7, 9, 1);
    ASSERT_TRUE(one);
    EXPECT_EQ(one.value(), std::vector<uint32_t>{7});
}

TEST(FlipbookFrames, MoreCellsThanFramesIsRefused) {
    const Result<std::vector<uint32_t>> r = sampleFrames(0, 9, 16);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("10 frames"), std::string::npos) << r.error().message;
}

CellImage uniform(float value) {
    CellImage image(2, 2);
    for (float& v : image.rgba)
        v = value;
    return image;
}

TEST(FlipbookLoop, LastCellsFadeTowardTheFramesBeforeTheFirst) {
    // Frames 0..7, 6 cells, 2 cross-faded: cells are frames 2..7, the last two mixed with 0 and 1.
    std::vector<CellImage> frames;
    for (int f = 0; f < 8; ++f)
        frames.push_back(uniform(float(f)));
    const std::vector<CellImage> cells = crossFadeLoop(frames, 2);
    ASSERT_EQ(cells.size(), 6u);
    for (int i = 0; i < 4; ++i)
        EXPECT_FLOAT_EQ(cells[i].rgba[0], float(i + 2));
    EXPECT_FLOAT_EQ(cells[4].rgba[0], (2.0f / 3.0f) * 6.0f + (1.0f / 3.0f) * 0.0f);
    EXPECT_FLOAT_EQ(cells[5].rgba[0], (1.0f / 3.0f) * 7.0f + (2.0f / 3.0f) * 1.0f);
    EXPECT_EQ(crossFadeLoop(frames, 0).size(), 8u);
}

TEST(FlipbookSheet, CellsGoLeftToRightThenTopToBottom) {
    FlipbookLayout layout{3, 2, 4, 2};
    std::vector<uint8_t> sheet(size_t(layout.sheetWidth()) * layout.sheetHeight() * 4, 0);
    for (uint32_t i = 0; i < layout.cells(); ++i)
        placeCell(sheet, layout, i, std::vector<uint8_t>(4 * 2 * 4, uint8_t(10 + i)));
    // Cell 4 is column 1, row 1: its top-left pixel at (4, 2) of the 12 x 4 sheet.
    EXPECT_EQ(sheet[(2 * 12 + 4) * 4], 14);
    EXPECT_EQ(sheet[(0 * 12 + 11) * 4], 12); // cell 2's top-right pixel
    EXPECT_EQ(sheet[(3 * 12 + 0) * 4], 13);  // cell 3's bottom-left pixel
    for (uint32_t i = 0; i < layout.cells(); ++i)
        EXPECT_EQ(cellOfSheet(sheet, layout, i), std::vector<uint8_t>(32, uint8_t(10 + i)));
}

TEST(FlipbookSheet, ColourIsPremultipliedLinearWithSrgbEncodedRgb) {
    CellImage cell(1, 1);
    cell.rgba = {0.5f, 0.25f, 0.0f, 0.5f};
    const std::vector<uint8_t> rgba = encodeColour8(cell);
    EXPECT_EQ(rgba[0], 188); // sRGB of 0.5 = 0.7354
    EXPECT_EQ(rgba[1], 137); // sRGB of 0.25 = 0.5371
    EXPECT_EQ(rgba[2], 0);
    EXPECT_EQ(rgba[3], 128); // alpha linear
}

TEST(FlipbookSheet, ToneMapIsTheScenesCurveOnColourAlone) {
    CellImage cell(1, 1);
    cell.rgba = {1.0f, 0.5f, 100.0f, 0.7f};
    toneMapCell(cell, 1.0f, true); // one stop up, then ACES
    auto aces = [](float x) {
        return (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
    };
    EXPECT_NEAR(cell.rgba[0], aces(2.0f), 1e-6f);
    EXPECT_NEAR(cell.rgba[1], aces(1.0f), 1e-6f);
    EXPECT_FLOAT_EQ(cell.rgba[2], 1.0f);
    EXPECT_FLOAT_EQ(cell.rgba[3], 0.7f);
}

TEST(FlipbookMotion, EncodingRoundTripsWithinItsStep) {
    MotionField field(4, 2);
    for (size_t k = 0; k < field.xy.size(); ++k)
        field.xy[k] = (float(k) - 7.0f) * 0.3f; // pixels, both signs
    const float scale = motionScale(std::span(&field, 1));
    EXPECT_NEAR(scale, 2.4f / 2.0f, 1e-6f); // the largest |y| (2.4 px) over the 2-pixel height
    const MotionField back = decodeMotion(encodeMotion(field, scale), 4, 2, scale);
    for (size_t k = 0; k < field.xy.size(); ++k) {
        const float side = k % 2 ? 2.0f : 4.0f;
        EXPECT_NEAR(back.xy[k], field.xy[k], scale * side / 255.0f + 1e-6f) << k;
    }
    const std::vector<uint8_t> still = encodeMotion(MotionField(2, 2), 1.0f);
    EXPECT_EQ(still[0], 128);
    EXPECT_EQ(still[3], 255);
}

using test::disc;

TEST(FlipbookFlow, FindsATranslationOfSeveralPixels) {
    const CellImage from = disc(64, 28.0f, 30.0f, 12.0f);
    const CellImage to = disc(64, 34.0f, 26.0f, 12.0f); // moved (+6, -4)
    const MotionField flow = opticalFlow(from, to);
    // Over the disc's inside, the mean flow is the translation within a quarter pixel.
    double sx = 0, sy = 0, n = 0;
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x)
            if (std::hypot(float(x) + 0.5f - 28.0f, float(y) + 0.5f - 30.0f) < 8.0f) {
                sx += double(flow.xy[(y * 64 + x) * 2]);
                sy += double(flow.xy[(y * 64 + x) * 2 + 1]);
                n += 1;
            }
    EXPECT_NEAR(sx / n, 6.0, 0.25);
    EXPECT_NEAR(sy / n, -4.0, 0.25);
}

TEST(FlipbookFlow, StillPicturesHaveNoMotion) {
    const CellImage image = disc(32, 16.0f, 16.0f, 8.0f);
    const MotionField flow = opticalFlow(image, image);
    for (float v : flow.xy)
        EXPECT_NEAR(v, 0.0f, 1e-4f);
}

TEST(FlipbookBlend, WildMotionSamplesNothing) {
    // Motion vectors far outside the picture, infinite or not a number blend in transparent black.
    const CellImage a = disc(8, 4.0f, 4.0f, 3.0f);
    MotionField wild(8, 8);
    const float values[] = {1e30f, -1e30f, INFINITY, NAN};
    for (size_t k = 0; k < wild.xy.size(); ++k)
        wild.xy[k] = values[k % 4];
    const CellImage out = blendCells(a, a, &wild, 0.5f);
    for (float v : out.rgba)
        EXPECT_EQ(v, 0.0f);
}

TEST(FlipbookBlend, MotionVectorsMatchTheInBetweenFrameBetterThanACrossFade) {
    // A disc moving 12 pixels: the frame halfway has it 6 pixels along.
    const CellImage a = disc(64, 20.0f, 32.0f, 10.0f);
    const CellImage b = disc(64, 32.0f, 32.0f, 10.0f);
    const CellImage half = disc(64, 26.0f, 32.0f, 10.0f);
    const MotionField flow = opticalFlow(a, b);
    const CellImage* cover[] = {&a, &b, &half};
    const double crossFade = coveredMeanError(blendCells(a, b, nullptr, 0.5f), half, cover);
    const double motion = coveredMeanError(blendCells(a, b, &flow, 0.5f), half, cover);
    EXPECT_LT(motion, 0.35 * crossFade) << "cross-fade " << crossFade << ", motion " << motion;
    // At t = 0 and 1 the blend is the cells themselves.
    EXPECT_LT(coveredMeanError(blendCells(a, b, &flow, 0.0f), a, cover), 1e-6);
    EXPECT_LT(coveredMeanError(blendCells(a, b, &flow, 1.0f), b, cover), 1e-6);
}

TEST(FlipbookBlend, CoveredErrorIgnoresEmptyPixels) {
    CellImage a(4, 1), b(4, 1);
    a.at(0, 0)[3] = 1.0f; // one covered pixel, differing by 1 in alpha
    const CellImage* cover[] = {&a, &b};
    EXPECT_DOUBLE_EQ(coveredMeanError(a, b, cover), 0.25);
    const CellImage* none[] = {&b};
    EXPECT_DOUBLE_EQ(coveredMeanError(b, b, none), 0.0);
}

TEST(SixWay, AxesAreTheCamerasFrameAndWeightsSumToOne) {
    scene::CameraSpec spec;
    spec.position = {2.0f, 1.0f, 3.0f};
    spec.target = {0.0f, 1.0f, 0.0f};
    const SceneCamera camera = makeCamera(spec, 1.0f);
    const std::array<glm::vec3, 6> axes = sixWayDirections(camera);
    const glm::vec3 towardViewer = glm::normalize(spec.position - spec.target);
    EXPECT_NEAR(glm::dot(axes[5], towardViewer), 1.0f, 1e-5f);  // front: the camera's side
    EXPECT_NEAR(glm::dot(axes[2], towardViewer), -1.0f, 1e-5f); // back: the far side
    EXPECT_NEAR(axes[1].y, 1.0f, 1e-5f);                        // top: up (a level camera)
    EXPECT_NEAR(glm::dot(axes[0], glm::cross(axes[1], axes[5])), 1.0f, 1e-5f); // right-handed
    for (size_t i = 0; i < 6; ++i) {
        const std::array<float, 6> w = sixWayWeights(camera, axes[i] * 3.0f);
        for (size_t j = 0; j < 6; ++j)
            EXPECT_NEAR(w[j], i == j ? 1.0f : 0.0f, 1e-6f) << i << " " << j;
    }
    for (glm::vec3 l : {glm::vec3(1, 2, 3), glm::vec3(-0.3f, 0.1f, -2.0f), glm::vec3(0, -1, 1)}) {
        const std::array<float, 6> w = sixWayWeights(camera, l);
        float sum = 0.0f;
        for (float v : w) {
            EXPECT_GE(v, 0.0f);
            sum += v;
        }
        EXPECT_NEAR(sum, 1.0f, 1e-5f);
    }
}

TEST(SixWay, MapsAreStoredStraightOverTheirScales) {
    SixWayCell cell{CellImage(2, 1), CellImage(2, 1)};
    // Pixel 0 half covered, lit 0.5, 1.0, 0.25 (premultiplied) from right, top, back, 0.1 from
    // the others, emission 0.2; pixel 1 empty.
    float a[4] = {0.5f, 1.0f, 0.25f, 0.5f}, b[4] = {0.1f, 0.1f, 0.1f, 0.2f};
    std::copy_n(a, 4, cell.a.at(0, 0));
    std::copy_n(b, 4, cell.b.at(0, 0));
    const SixWayScales scales = sixWayScales(std::span(&cell, 1));
    EXPECT_FLOAT_EQ(scales.light, 2.0f);    // top: 1.0 / 0.5
    EXPECT_FLOAT_EQ(scales.emission, 0.4f); // 0.2 / 0.5
    const std::array<std::vector<uint8_t>, 2> stored = encodeSixWay(cell, scales);
    EXPECT_EQ(stored[0][0], 128); // 1.0 straight over 2
    EXPECT_EQ(stored[0][1], 255);
    EXPECT_EQ(stored[0][2], 64);
    EXPECT_EQ(stored[0][3], 128); // opacity
    EXPECT_EQ(stored[1][0], 26);  // 0.2 straight over 2
    EXPECT_EQ(stored[1][3], 255); // emission at its scale
    EXPECT_EQ(stored[0][4 + 3], 0);
    // Relit from the top alone: the top map again, premultiplied.
    std::array<float, 6> top{};
    top[1] = 1.0f;
    const CellImage relit = relightSixWay(stored[0], stored[1], 2, 1, scales, top);
    EXPECT_NEAR(relit.at(0, 0)[0], 1.0f, 2.0f / 255.0f);
    EXPECT_NEAR(relit.at(0, 0)[3], 0.5f, 1.0f / 255.0f);
    EXPECT_FLOAT_EQ(relit.at(1, 0)[0], 0.0f);
}

TEST(SmokeMotion, TheVelocityCarriedToTheScreen) {
    // A cube of smoke moving right and up at 1 m/s, seen from 5 m straight in front: over 0.1 s it
    // moves 0.1 m, which is 0.1 / (5 tan 20 deg) of the picture's half height.
    fluid::GridShape shape{16, 16, 16, 0.05f};
    fluid::FieldState state = fluid::FieldState::zero(shape);
    std::fill(state.velocityX.begin(), state.velocityX.end(), 1.0f);
    std::fill(state.velocityY.begin(), state.velocityY.end(), 1.0f);
    for (uint32_t k = 4; k < 12; ++k)
        for (uint32_t j = 4; j < 12; ++j)
            for (uint32_t i = 4; i < 12; ++i)
                state.pigment[4 * shape.index(i, j, k) + 3] = 1.0f;
    const SmokeFields grid{&state, glm::vec3(-0.4f)}; // centred on the origin
    scene::CameraSpec spec;
    spec.position = {0.0f, 0.0f, 5.0f};
    spec.target = {0.0f, 0.0f, 0.0f};
    spec.fovDegrees = 40.0f;
    const SceneCamera camera = makeCamera(spec, 1.0f);
    const MotionField field = projectedSmokeMotion(std::span(&grid, 1), camera, 64, 64, 0.1f, 8.0f);
    const float expected = 0.1f / (5.0f * std::tan(glm::radians(20.0f))) * 32.0f;
    // At the centre, where the front face of the cube is what the pixel shows (0.2 m nearer).
    const float* centre = &field.xy[(32 * 64 + 32) * 2];
    EXPECT_NEAR(centre[0], expected * 5.0f / 4.8f, 0.05f * expected);  // right: +x
    EXPECT_NEAR(centre[1], -expected * 5.0f / 4.8f, 0.05f * expected); // up: -y (rows down)
    // Outside the smoke, no motion.
    EXPECT_EQ(field.xy[0], 0.0f);
    EXPECT_EQ(field.xy[1], 0.0f);
}

TEST(ExrOutput, HalfChannelsInTheFileLayout) {
    // 3 x 2 pixels, pixel (x, y) = (x, y, 10 + x, 0.5): read back where the layout puts them.
    std::vector<float> rgba;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x)
            rgba.insert(rgba.end(), {float(x), float(y), 10.0f + float(x), 0.5f});
    const std::string path = std::string(MFX_TEST_OUTPUT_DIR) + "/exr_layout.exr";
    ASSERT_TRUE(writeExr(path, 3, 2, rgba));
    std::ifstream in(path, std::ios::binary);
    const std::vector<uint8_t> file((std::istreambuf_iterator<char>(in)),
                                    std::istreambuf_iterator<char>());
    auto u32 = [&](size_t at) {
        uint32_t v;
        std::memcpy(&v, &file[at], 4);
        return v;
    };
    ASSERT_GT(file.size(), 8u);
    EXPECT_EQ(u32(0), 20000630u);
    EXPECT_EQ(u32(4), 2u);
    // The offset table follows the header's closing 0; two lines of 8 + 3 * 4 * 2 bytes end the
    // file.
    const size_t lineBytes = 3 * 4 * 2;
    const size_t table = file.size() - 2 * (8 + lineBytes) - 2 * 8;
    EXPECT_EQ(file[table - 1], 0);
    uint64_t offsets[2];
    std::memcpy(offsets, &file[table], 16);
    EXPECT_EQ(offsets[0], table + 16);
    EXPECT_EQ(offsets[1], table + 16 + 8 + lineBytes);
    // Line 1: y, byte count, then A, B, G, R of its three pixels.
    const size_t line = size_t(offsets[1]);
    EXPECT_EQ(u32(line), 1u);
    EXPECT_EQ(u32(line + 4), lineBytes);
    auto value = [&](int channel, int x) {
        uint16_t h;
        std::memcpy(&h, &file[line + 8 + size_t(channel) * 6 + size_t(x) * 2], 2);
        return glm::unpackHalf1x16(h);
    };
    for (int x = 0; x < 3; ++x) {
        EXPECT_EQ(value(0, x), 0.5f);             // A
        EXPECT_EQ(value(1, x), 10.0f + float(x)); // B
        EXPECT_EQ(value(2, x), 1.0f);             // G = y
        EXPECT_EQ(value(3, x), float(x));         // R
    }
}

} // namespace
} // namespace mfx::render
