// Textured speed-line ribbons (scene::RibbonTexture; shaders/render/ribbon_texture.glsl,
// ribbon_distance.comp): the keys and their refusals, the texture file's checks (inside the
// scene's folder, a PNG of bounded size), and, on the GPU, where the texture lands along a ribbon
// drawn by a point whose speed changes: tiled by distance, the same repeats per metre at 1 and at
// 4 m/s and fixed where it was drawn; tiled by age, stretched fourfold where the point is fast;
// stretch, once from the head to the oldest sample; per segment, once per frame; the scroll and
// the erosion where the formulas put them.
#include "core/gpu/commands.h"
#include "core/scene/kinds/trail_effects.h"
#include "core/scene/ribbon_texture.h"
#include "render/bake_renderer.h"
#include "render/image_output.h"
#include "sim/scene_simulation.h"
#include "tests/gpu_test.h"
#include "tests/moving_point.h"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

namespace mfx::test {
namespace {

namespace fs = std::filesystem;

// A fresh folder in the tests' output folder.
fs::path freshFolder(const std::string& name) {
    const fs::path dir = fs::path(MFX_TEST_OUTPUT_DIR) / "ribbon_texture" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void writeText(const fs::path& file, const std::string& text) {
    std::ofstream(file, std::ios::binary) << text;
}

// An 8x2 RGBA PNG, white, whose alpha over u is `alpha(column)`.
void writeTexture(const fs::path& file, const std::function<uint8_t(int)>& alpha) {
    std::vector<uint8_t> rgba;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 8; ++x)
            rgba.insert(rgba.end(), {255, 255, 255, alpha(x)});
    ASSERT_TRUE(render::writePng(file.string(), 8, 2, rgba).ok());
}
// Opaque over the first half of each repeat (u in [0, 0.5)), clear over the second.
void writeStripes(const fs::path& file) {
    writeTexture(file, [](int x) { return uint8_t(x < 4 ? 255 : 0); });
}

// --- The keys ----------------------------------------------------------------------------------

Result<scene::Scene> parseLines(const std::string& keys) {
    return scene::parseScene(R"({"effects": [{"type": "speed_lines")" + keys + "}]}", "t.json");
}

TEST(RibbonTextureKeys, AreReadWithTheirDefaults) {
    Result<scene::Scene> plain = parseLines("");
    ASSERT_TRUE(plain) << plain.error().message;
    const scene::RibbonTexture& none =
        plain.value().effects[0].as<scene::SpeedLinesSpec>()->ribbon.texture;
    EXPECT_TRUE(none.file.empty());
    EXPECT_EQ(none.uv, scene::TextureUv::Stretch);
    EXPECT_TRUE(none.erosionOverLife.empty());

    Result<scene::Scene> s = parseLines(
        R"(, "texture": "tex/slash.png", "texture_uv": "distance", "texture_repeats": 3,
           "texture_tile": 0.4, "texture_scroll": -2, "erosion_softness": 0.3,
           "erosion_over_life": [{"at": 0, "threshold": 0}, {"at": 1, "threshold": 0.9}])");
    ASSERT_TRUE(s) << s.error().message;
    const scene::RibbonTexture& t =
        s.value().effects[0].as<scene::SpeedLinesSpec>()->ribbon.texture;
    EXPECT_EQ(t.file, "tex/slash.png");
    EXPECT_EQ(t.uv, scene::TextureUv::Distance);
    EXPECT_FLOAT_EQ(t.repeats, 3.0f);
    EXPECT_FLOAT_EQ(t.tileLength, 0.4f);
    EXPECT_FLOAT_EQ(t.scroll, -2.0f);
    EXPECT_FLOAT_EQ(t.erosionSoftness, 0.3f);
    ASSERT_EQ(t.erosionOverLife.size(), 2u);
    EXPECT_FLOAT_EQ(t.erosionOverLife[1].value, 0.9f);
    for (const char* mode : {"stretch", "per_segment", "tiled", "distance"})
        EXPECT_TRUE(parseLines(std::string(R"(, "texture_uv": ")") + mode + "\"")) << mode;
}

TEST(RibbonTextureKeys, RefuseNamesOutsideTheScenesFolderAndBadValuesWithTheirKey) {
    const std::pair<const char*, const char*> refused[] = {
        {R"(, "texture": "/etc/passwd")", "effects[0].texture: \"/etc/passwd\" is not relative"},
        {R"(, "texture": "../secret.png")", "leads out of the scene's folder"},
        {R"(, "texture": "a/../../b.png")", "leads out of the scene's folder"},
        {R"(, "texture": "a\u0000b.png")", "NUL"},
        {R"(, "texture": 3)", "effects[0].texture: expected a string"},
        {R"(, "texture_uv": "mirror")", "effects[0].texture_uv: \"mirror\" is not one of"},
        {R"(, "texture_tile": 0)", "effects[0].texture_tile"},
        {R"(, "texture_repeats": -1)", "effects[0].texture_repeats"},
        {R"(, "texture_scroll": 1e9)", "effects[0].texture_scroll"},
        {R"(, "erosion_softness": 0)", "effects[0].erosion_softness"},
        {R"(, "erosion_over_life": [{"at": 0, "threshold": 1.5}, {"at": 1, "threshold": 0}])",
         "threshold"},
    };
    for (const auto& [keys, message] : refused) {
        Result<scene::Scene> s = parseLines(keys);
        ASSERT_FALSE(s) << keys;
        EXPECT_NE(s.error().message.find(message), std::string::npos) << s.error().message;
        EXPECT_EQ(s.error().message.find('\n'), std::string::npos) << s.error().message;
    }
    // A ribbon kind without textures refuses the keys.
    Result<scene::Scene> particles = scene::parseScene(
        R"({"effects": [{"type": "motion_particles", "texture": "a.png"}]})", "t.json");
    EXPECT_FALSE(particles);
}

// --- The file ----------------------------------------------------------------------------------

// A scene file in `dir` whose one speed-line effect has `texture`.
fs::path sceneWithTexture(const fs::path& dir, const std::string& texture) {
    const fs::path file = dir / "scene.json";
    writeText(file, R"({"effects": [{"type": "speed_lines", "texture": ")" + texture + "\"}]}");
    return file;
}

TEST(RibbonTextureFile, LoadsAPngFromTheScenesFolder) {
    const fs::path dir = freshFolder("load");
    fs::create_directories(dir / "tex");
    writeStripes(dir / "tex" / "stripes.png");
    Result<scene::Scene> s = scene::loadScene(sceneWithTexture(dir, "tex/stripes.png"));
    ASSERT_TRUE(s) << s.error().message;
    Result<scene::TextureImage> image = scene::loadEffectTexture(s.value(), 0);
    ASSERT_TRUE(image) << image.error().message;
    EXPECT_EQ(image.value().width, 8u);
    EXPECT_EQ(image.value().height, 2u);
    ASSERT_EQ(image.value().rgba.size(), 8u * 2u * 4u);
    EXPECT_EQ(image.value().rgba[3], 255);       // texel (0, 0)
    EXPECT_EQ(image.value().rgba[4 * 4 + 3], 0); // texel (4, 0)
}

// The scene's loading refuses each bad file in one line naming the effect's key.
void expectRefused(const fs::path& scene, const std::string& message) {
    Result<scene::Scene> s = scene::loadScene(scene);
    ASSERT_FALSE(s) << scene;
    EXPECT_NE(s.error().message.find("effects[0].texture: "), std::string::npos)
        << s.error().message;
    EXPECT_NE(s.error().message.find(message), std::string::npos) << s.error().message;
    EXPECT_EQ(s.error().message.find('\n'), std::string::npos) << s.error().message;
}

// The first bytes of a PNG whose header says `width` x `height`, and nothing after.
std::string pngHeader(uint32_t width, uint32_t height) {
    std::string bytes = "\x89PNG\r\n\x1a\n";
    auto be32 = [&](uint32_t v) {
        for (int shift = 24; shift >= 0; shift -= 8)
            bytes.push_back(char((v >> shift) & 0xff));
    };
    be32(13);
    bytes += "IHDR";
    be32(width);
    be32(height);
    bytes += std::string("\x08\x06\x00\x00\x00", 5);
    be32(0); // a CRC (not checked before the size)
    return bytes;
}

TEST(RibbonTextureFile, RefusesWhatIsNoBoundedPngInsideTheFolder) {
    const fs::path root = freshFolder("refuse");
    const fs::path dir = root / "scene";
    fs::create_directories(dir);
    expectRefused(sceneWithTexture(dir, "missing.png"), "no file");
    fs::create_directories(dir / "folder.png");
    expectRefused(sceneWithTexture(dir, "folder.png"), "not a regular file");
    writeText(dir / "text.png", "this is no picture");
    expectRefused(sceneWithTexture(dir, "text.png"), "not a PNG file");
    writeText(dir / "cut.png", pngHeader(8, 8).substr(0, 20));
    expectRefused(sceneWithTexture(dir, "cut.png"), "without its header");
    // Refused by its header, before anything is decoded (it would take 4 GiB).
    writeText(dir / "huge.png", pngHeader(32768, 32768));
    expectRefused(sceneWithTexture(dir, "huge.png"), "32768x32768 texels");
    writeText(dir / "empty.png", pngHeader(0, 4));
    expectRefused(sceneWithTexture(dir, "empty.png"), "0x4 texels");
    writeText(dir / "damaged.png", pngHeader(8, 2) + "IDATgarbage");
    expectRefused(sceneWithTexture(dir, "damaged.png"), "cannot be decoded");
    // A file over the bound (sparse: nothing is written).
    writeText(dir / "big.png", pngHeader(8, 2));
    fs::resize_file(dir / "big.png", scene::kMaxTextureFileBytes + 1);
    expectRefused(sceneWithTexture(dir, "big.png"), "over 32 MiB");
    // A link out of the folder, though the name stays inside it.
    writeStripes(root / "outside.png");
    fs::create_symlink(root / "outside.png", dir / "link.png");
    expectRefused(sceneWithTexture(dir, "link.png"), "leads out of the scene's folder");
}

TEST(RibbonTextureFile, DecodingRefusesBytesThatAreNoPng) {
    EXPECT_FALSE(scene::decodeTexturePng({}));
    const std::string header = pngHeader(4, 4);
    std::vector<uint8_t> bytes(header.begin(), header.end());
    EXPECT_FALSE(scene::decodeTexturePng(bytes)); // a header and no picture
    bytes[8 + 4] = 'X';                           // no IHDR
    Result<scene::TextureImage> r = scene::decodeTexturePng(bytes);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("without its header"), std::string::npos);
}

// --- On the GPU: where the texture lands ---------------------------------------------------------

// The moving point at 1 m/s from x = -1.2 to -0.6 (0 to 0.6 s), then at 4 m/s to 0.6 (0.9 s),
// 0.6 m above the floor.
anim::Character changingSpeedPoint() {
    anim::Character c = movingPoint();
    anim::Channel& ch = c.clips[0].channels[0];
    ch.times = {0.0f, 0.6f, 0.9f, 2.0f};
    ch.values = {glm::vec4(-1.2f, 0.6f, 0, 0), glm::vec4(-0.6f, 0.6f, 0, 0),
                 glm::vec4(0.6f, 0.6f, 0, 0), glm::vec4(0.6f, 0.6f, 0, 0)};
    return c;
}
// When the point was at x (on its way, -1.2 to 0.6).
float timeAt(float x) {
    return x <= -0.6f ? x + 1.2f : 0.6f + (x + 0.6f) / 4.0f;
}

constexpr uint32_t kWidth = 960, kHeight = 540;
constexpr float kFps = 30.0f;
constexpr uint32_t kFrames = 28; // the last is at 0.9 s, the point at x = 0.6
constexpr uint32_t kLifetime = 40;
const float kNow = float(kFrames - 1) / kFps;

// The ribbon's alpha along its centre line (y = 0.6, z = 0), by x, drawn by the changing-speed
// point with `textureKeys` (a flat, camera-facing white ribbon 0.1 m wide, alpha blended, even
// along its length: its alpha is the texture's), the texture `texture` beside the scene file.
struct CentreLine {
    std::function<float(float)> alpha; // at x (m)
    float pixelsPerMetre = 0.0f;
};
using TexturedRibbonTest = GpuTest;

CentreLine drawRibbon(gpu::Context& ctx, const std::string& name, const std::string& textureKeys,
                      const std::function<void(const fs::path&)>& texture,
                      uint32_t lifetime = kLifetime) {
    const fs::path dir = freshFolder(name);
    texture(dir / "texture.png");
    const fs::path file = dir / "scene.json";
    writeText(
        file,
        R"({"camera": {"position": [-0.3, 0.6, 2.2], "target": [-0.3, 0.6, 0], "fov_degrees": 60},
                  "output": {"width": 960, "height": 540, "fps": 30, "frames": 28},
                  "effects": [{"type": "speed_lines", "stride": 1, "width": 0.1,
                               "sub_samples": 4, "alpha_start": 1, "alpha_end": 1, "core": 0,
                               "colour_over_life": [{"at": 0, "colour": [1, 1, 1, 1]},
                                                    {"at": 1, "colour": [1, 1, 1, 1]}],
                               "width_over_life": [{"at": 0, "width": 1}, {"at": 1, "width": 1}],
                               "texture": "texture.png", "lifetime": )" +
            std::to_string(lifetime) + textureKeys + "}]}");
    Result<scene::Scene> s = scene::loadScene(file);
    EXPECT_TRUE(s) << s.error().message;
    if (!s) return {};
    const anim::Character point = changingSpeedPoint();
    auto sim = sim::SceneSimulation::create(ctx, s.value(), point);
    EXPECT_TRUE(sim) << sim.error().message;
    if (!sim) return {};
    render::BakeRenderer renderer(ctx, *sim.value(), kWidth, kHeight, false, VK_SAMPLE_COUNT_1_BIT);
    renderer.setCamera(
        render::makeCamera(sim.value()->scene().camera, float(kWidth) / float(kHeight)));
    for (uint32_t f = 0; f < sim.value()->frameCount(); ++f)
        gpu::submitOneShot(ctx,
                           [&](VkCommandBuffer cmd) { renderer.record(cmd, *sim.value(), f); });
    auto coverage =
        std::make_shared<std::vector<float>>(render::readLinearColor(ctx, renderer.layer()));
    const glm::mat4 viewProjection = renderer.camera().viewProjection;
    auto pixel = [viewProjection](float x) {
        const glm::vec4 clip = viewProjection * glm::vec4(x, 0.6f, 0.0f, 1.0f);
        return glm::vec2((clip.x / clip.w * 0.5f + 0.5f) * float(kWidth),
                         (0.5f - clip.y / clip.w * 0.5f) * float(kHeight));
    };
    CentreLine line;
    line.pixelsPerMetre = glm::distance(pixel(0.0f), pixel(1.0f));
    line.alpha = [coverage, pixel](float x) {
        const glm::vec2 q = pixel(x) - 0.5f;
        const int x0 = int(std::floor(q.x)), y0 = int(std::floor(q.y));
        const float fx = q.x - float(x0), fy = q.y - float(y0);
        auto a = [&](int px, int py) {
            if (px < 0 || py < 0 || px >= int(kWidth) || py >= int(kHeight)) return 0.0f;
            return (*coverage)[(size_t(py) * kWidth + size_t(px)) * 4 + 3];
        };
        return (1 - fy) * ((1 - fx) * a(x0, y0) + fx * a(x0 + 1, y0)) +
               fy * ((1 - fx) * a(x0, y0 + 1) + fx * a(x0 + 1, y0 + 1));
    };
    return line;
}

// An edge of the stripes along the line: where the alpha crosses 0.5, rising or falling as x grows.
struct Edge {
    float x;
    bool rising;
};
// Between x0 and x1: measured on the picture (every millimetre, linear between), or predicted from
// the texture's u at x (opaque where fract(u) < 0.5).
std::vector<Edge> measuredEdges(const CentreLine& line, float x0, float x1) {
    std::vector<Edge> edges;
    float previous = line.alpha(x0);
    for (float x = x0 + 0.001f; x <= x1; x += 0.001f) {
        const float here = line.alpha(x);
        if ((previous < 0.5f) != (here < 0.5f))
            edges.push_back(
                {x - 0.001f + 0.001f * (0.5f - previous) / (here - previous), here >= 0.5f});
        previous = here;
    }
    return edges;
}
std::vector<Edge> predictedEdges(const std::function<float(float)>& u, float x0, float x1) {
    std::vector<Edge> edges;
    auto opaque = [&](float x) { return u(x) - std::floor(u(x)) < 0.5f; };
    bool previous = opaque(x0);
    for (float x = x0 + 1e-4f; x <= x1; x += 1e-4f) {
        const bool here = opaque(x);
        if (here != previous) edges.push_back({x - 0.5e-4f, here});
        previous = here;
    }
    return edges;
}

// Each measured edge where the prediction puts it, within `pixels`, rising or falling alike.
void expectEdges(const CentreLine& line, const std::vector<Edge>& measured,
                 const std::vector<Edge>& predicted, float pixels) {
    ASSERT_EQ(measured.size(), predicted.size());
    for (size_t i = 0; i < measured.size(); ++i) {
        EXPECT_NEAR(measured[i].x, predicted[i].x, pixels / line.pixelsPerMetre) << "edge " << i;
        EXPECT_EQ(measured[i].rising, predicted[i].rising) << "edge " << i;
    }
}

// The mean distance between successive edges both inside [x0, x1].
float meanSpacing(const std::vector<Edge>& edges, float x0, float x1) {
    float sum = 0.0f;
    int n = 0;
    for (size_t i = 0; i + 1 < edges.size(); ++i)
        if (edges[i].x >= x0 && edges[i + 1].x <= x1) {
            sum += edges[i + 1].x - edges[i].x;
            ++n;
        }
    return n > 0 ? sum / float(n) : 0.0f;
}

// Along the ribbon, away from its two ends (the point starts at x = -1.2 and is at 0.6 now), and
// from the places where the tests' stripes have their edges (every 5 cm from the start).
constexpr float kFrom = -1.13f, kTo = 0.53f;
constexpr float kSlowTo = -0.62f, kFastFrom = -0.58f; // the speed changes at x = -0.6

TEST_F(TexturedRibbonTest, TiledByDistanceKeepsItsRepeatsPerMetreWhereTheSpeedChanges) {
    // A repeat every 0.2 m: an edge every 0.1 m, at 1 m/s as at 4 m/s. A lifetime of 20 frames:
    // the first 8 frames' segments have aged out, the tail is at x = -0.967 (t = 0.233 s), yet the
    // pattern stays where it was drawn, counted from where the line began.
    const CentreLine line = drawRibbon(ctx(), "distance", R"(, "texture_uv": "distance",
                                       "texture_tile": 0.2)",
                                       writeStripes, 20);
    ASSERT_TRUE(line.alpha);
    const float from = -0.93f; // past the tail
    EXPECT_LT(line.alpha(-1.0f), 0.01f) << "aged out";
    const std::vector<Edge> edges = measuredEdges(line, from, kTo);
    const float slow = meanSpacing(edges, from, kSlowTo), fast = meanSpacing(edges, kFastFrom, kTo);
    std::printf("distance: %zu edges, %.4f m apart at 1 m/s, %.4f m at 4 m/s (%.1f px/m)\n",
                edges.size(), double(slow), double(fast), double(line.pixelsPerMetre));
    EXPECT_NEAR(slow, 0.1f, 0.002f);
    EXPECT_NEAR(fast, 0.1f, 0.002f);
    // And fixed where they were drawn: u = -(distance from the start) / tile.
    expectEdges(line, edges, predictedEdges([](float x) { return -(x + 1.2f) / 0.2f; }, from, kTo),
                1.0f);

    // Tiled by age instead (the same spacing at 1 m/s): four times as far apart at 4 m/s.
    const float repeats = float(kLifetime) / kFps / 0.2f; // a repeat every 0.2 s of age
    const CentreLine aged = drawRibbon(
        ctx(), "tiled", R"(, "texture_uv": "tiled", "texture_repeats": )" + std::to_string(repeats),
        writeStripes);
    ASSERT_TRUE(aged.alpha);
    const std::vector<Edge> agedEdges = measuredEdges(aged, kFrom, kTo);
    const float agedSlow = meanSpacing(agedEdges, kFrom, kSlowTo),
                agedFast = meanSpacing(agedEdges, kFastFrom, kTo);
    std::printf("tiled by age: %.4f m apart at 1 m/s, %.4f m at 4 m/s\n", double(agedSlow),
                double(agedFast));
    EXPECT_NEAR(agedSlow, 0.1f, 0.003f);
    EXPECT_NEAR(agedFast, 0.4f, 0.02f);
    expectEdges(
        aged, agedEdges,
        predictedEdges(
            [&](float x) { return (kNow - timeAt(x)) * repeats / (float(kLifetime) / kFps); },
            kFrom, kTo),
        1.0f);
}

TEST_F(TexturedRibbonTest, StretchMapsTheTextureOnceFromTheHeadToTheOldestSample) {
    const CentreLine line = drawRibbon(ctx(), "stretch", "", writeStripes);
    ASSERT_TRUE(line.alpha);
    // Opaque over the first half of u: from the head back to half the ribbon's age span, which
    // runs from now to a frame before the first segment (t = -1/30 s).
    const float span = kNow + 1.0f / kFps;
    const std::vector<Edge> edges = measuredEdges(line, kFrom, kTo);
    ASSERT_EQ(edges.size(), 1u) << "the texture is mapped once: one edge";
    EXPECT_TRUE(edges[0].rising);
    const float expected = -1.2f + (kNow - span / 2.0f); // in the slow part: x = t - 1.2
    std::printf("stretch: the edge at x = %.4f m (expected %.4f)\n", double(edges[0].x),
                double(expected));
    EXPECT_NEAR(edges[0].x, expected, 1.0f / line.pixelsPerMetre);
    EXPECT_GT(line.alpha(0.5f), 0.95f);  // by the head
    EXPECT_LT(line.alpha(-1.1f), 0.05f); // by the tail
}

TEST_F(TexturedRibbonTest, PerSegmentMapsTheTextureOnceOverEachFramesSegment) {
    const CentreLine line =
        drawRibbon(ctx(), "segment", R"(, "texture_uv": "per_segment")", writeStripes);
    ASSERT_TRUE(line.alpha);
    // u = tau: 0 at the segment's frame, 1 at the frame before (13 cm apart at 4 m/s).
    const std::vector<Edge> edges = measuredEdges(line, kFastFrom, kTo);
    std::printf("per segment: %zu edges at 4 m/s\n", edges.size());
    expectEdges(line, edges,
                predictedEdges(
                    [](float x) {
                        const float frames = timeAt(x) * kFps;
                        // Just past a frame boundary the sample is the next frame's segment's
                        // oldest.
                        return std::ceil(frames - 1e-5f) - frames;
                    },
                    kFastFrom, kTo),
                1.0f);
}

TEST_F(TexturedRibbonTest, ScrollingMovesThePatternTowardsTheTail) {
    // A quarter of a repeat by now: scroll * now = 0.25.
    const float scroll = 0.25f / kNow;
    const CentreLine line = drawRibbon(ctx(), "scroll",
                                       R"(, "texture_uv": "distance", "texture_tile": 0.2,
                                       "texture_scroll": )" +
                                           std::to_string(scroll),
                                       writeStripes);
    ASSERT_TRUE(line.alpha);
    // u = -distance / tile - scroll * now: each texel 5 cm nearer the tail than unscrolled.
    expectEdges(
        line, measuredEdges(line, kFrom, kTo),
        predictedEdges([&](float x) { return -(x + 1.2f) / 0.2f - scroll * kNow; }, kFrom, kTo),
        1.0f);
}

TEST_F(TexturedRibbonTest, ErosionEatsTheTexelsBelowTheThresholdOfTheirLife) {
    // Texels of alpha 0.5 everywhere, the threshold rising from 0 at the head to 1 at the end of
    // life: the alpha is 0.5 * smoothstep(e - s, e, 0.5), e = threshold * (1 + s), which halves
    // where the threshold is about 0.5 (s = 0.1): near life 0.5, 20 frames of age.
    const CentreLine line =
        drawRibbon(ctx(), "erosion",
                   R"(, "erosion_over_life": [{"at": 0, "threshold": 0}, {"at": 1, "threshold": 1}],
                   "erosion_softness": 0.1)",
                   [](const fs::path& f) { writeTexture(f, [](int) { return uint8_t(128); }); });
    ASSERT_TRUE(line.alpha);
    const float half = 128.0f / 255.0f;
    EXPECT_NEAR(line.alpha(0.4f), half, 0.01f); // young: kept
    EXPECT_LT(line.alpha(-1.1f), 0.005f);       // life 0.7 and past: eaten
    // Where it falls through half its alpha: smoothstep = 1/2 where e = alpha + s / 2.
    const float life = (half + 0.05f) / 1.1f;
    const float at = -1.2f + (kNow - life * float(kLifetime) / kFps); // in the slow part
    float crossing = 0.0f;
    for (float x = kFrom; x < kTo; x += 0.001f)
        if (line.alpha(x) < 0.5f * half && line.alpha(x + 0.001f) >= 0.5f * half) crossing = x;
    std::printf("erosion: half gone at x = %.4f m (expected %.4f)\n", double(crossing), double(at));
    EXPECT_NEAR(crossing, at, 1.5f / line.pixelsPerMetre);
}

} // namespace
} // namespace mfx::test
