// The cartoon smoke look (scene::CartoonSmoke, shaders/render/smoke_cartoon.glsl and
// smoke_cartoon_composite.frag): a ball of pigment whose alpha falls linearly from its centre,
// a(r) = 1 - r / R0, has its threshold surface at r = R0 (1 - threshold), a sphere. Seen from a
// point on its axis, that sphere's silhouette is a circle of radius f tan(asin(r / D)) pixels (f
// the focal length in pixels, D the distance to its centre). Drawn over white with no billows, the
// picture must show that circle within a pixel, exactly `bands` flat tones inside an ink ring
// `outline_width` pixels wide, by both marches, over a dense and a sparse grid.
#include "core/gpu/commands.h"
#include "core/scene/kinds/smoke_effect.h"
#include "core/scene/scene.h"
#include "fluid/smoke_solver.h"
#include "render/image_output.h"
#include "render/smoke_pass.h"
#include "tests/gpu_test.h"

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <map>
#include <numbers>

namespace mfx::test {
namespace {

using SmokeCartoonTest = GpuTest;

constexpr uint32_t kWidth = 400, kHeight = 300;
constexpr uint32_t kCells = 32;
constexpr float kCell = 0.05f;
constexpr float kBallRadius = 0.6f;        // R0: where the alpha reaches 0
constexpr float kDistance = 3.0f;          // eye to the ball's centre
const glm::vec3 kCentre(0.0f, 1.0f, 0.0f); // the ball's centre in the world
constexpr float kFovDegrees = 40.0f;

fluid::FieldState ballState(const fluid::GridShape& grid) {
    fluid::FieldState state = fluid::FieldState::zero(grid);
    for (uint32_t z = 0; z < grid.cellsZ; ++z)
        for (uint32_t y = 0; y < grid.cellsY; ++y)
            for (uint32_t x = 0; x < grid.cellsX; ++x) {
                const glm::vec3 d =
                    (glm::vec3(x, y, z) + 0.5f - float(kCells) / 2.0f) * grid.cellSize;
                const float a = glm::clamp(1.0f - glm::length(d) / kBallRadius, 0.0f, 1.0f);
                const size_t i = grid.index(x, y, z) * 4;
                state.pigment[i + 0] = state.pigment[i + 1] = state.pigment[i + 2] = a;
                state.pigment[i + 3] = a;
            }
    return state;
}

// The ball's silhouette radius in pixels for a threshold.
double analyticRadius(float threshold) {
    const double r = kBallRadius * (1.0 - threshold);
    const double focal = 0.5 * kHeight / std::tan(0.5 * kFovDegrees * std::numbers::pi / 180.0);
    return focal * std::tan(std::asin(r / kDistance));
}

struct Picture {
    std::vector<float> linear; // RGBA, rows top first
    float at(uint32_t x, uint32_t y, int c) const {
        return linear[(size_t(y) * kWidth + x) * 4 + c];
    }
};

scene::SmokeShading cartoonShading(uint32_t bands, float outlineWidth, float threshold) {
    scene::SmokeShading shading = scene::smokeShading(scene::SmokePreset::Cartoon);
    shading.cartoon.bands = bands;
    shading.cartoon.outlineWidth = outlineWidth;
    shading.cartoon.threshold = threshold;
    shading.cartoon.billow = 0.0f; // the analytic sphere
    return shading;
}

// The volume drawn over a white picture with nothing in it, from kDistance in front of the ball,
// lit from the upper left.
Picture shoot(gpu::Context& ctx, const render::SmokePass::Volume& volume, render::SmokeMarch march,
              const std::string& png) {
    scene::CameraSpec cameraSpec;
    cameraSpec.position = kCentre + glm::vec3(0.0f, 0.0f, kDistance);
    cameraSpec.target = kCentre;
    cameraSpec.fovDegrees = kFovDegrees;
    const render::SceneCamera camera =
        render::makeCamera(cameraSpec, float(kWidth) / float(kHeight));
    scene::LightSpec key;
    key.direction = glm::vec3(0.6f, -0.6f, -0.5f);
    render::SmokeLook look;
    look.march = march;
    render::RenderTarget target = render::createRenderTarget(ctx, kWidth, kHeight);
    render::SmokePass pass(ctx);
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        render::beginRendering(cmd, target, glm::vec4(1.0f));
        render::endRendering(cmd);
        pass.draw(cmd, target, std::span(&volume, 1), camera, key, look);
    });
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/smoke_cartoon";
    EXPECT_TRUE(render::ensureOutputDirectory(dir).ok());
    EXPECT_TRUE(
        render::writePng(dir + "/" + png, kWidth, kHeight, render::readColor(ctx, target)).ok());
    return {render::readLinearColor(ctx, target)};
}

// How much of the smoke covers a point over white near the silhouette, where the smoke is ink:
// (1 - colour) / (1 - ink), over the channels, bilinear between the pixel centres around it.
float coverage(const Picture& p, float x, float y, const glm::vec3& ink) {
    const float fx = x - 0.5f, fy = y - 0.5f;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const float tx = fx - float(x0), ty = fy - float(y0);
    auto one = [&](int px, int py) {
        px = std::clamp(px, 0, int(kWidth) - 1);
        py = std::clamp(py, 0, int(kHeight) - 1);
        float sum = 0.0f;
        for (int c = 0; c < 3; ++c)
            sum += (1.0f - p.at(uint32_t(px), uint32_t(py), c)) / (1.0f - ink[c]);
        return sum / 3.0f;
    };
    return (1.0f - ty) * ((1.0f - tx) * one(x0, y0) + tx * one(x0 + 1, y0)) +
           ty * ((1.0f - tx) * one(x0, y0 + 1) + tx * one(x0 + 1, y0 + 1));
}

struct Measured {
    double worstRadiusError = 0.0; // pixels, of the silhouette against the analytic circle
    double meanRadius = 0.0;
    double narrowestInk = 1e9, widestInk = 0.0; // pixels along the radii
    std::map<std::array<int, 3>, int> tones;    // fully covered colours (1/1024 steps): pixels
};

bool near(const glm::vec3& a, const glm::vec3& b) {
    return glm::all(glm::lessThan(glm::abs(a - b), glm::vec3(2e-3f)));
}

// Along 64 radii from the picture's centre: where the coverage crosses 1/2 (the silhouette) and
// how far in from it the ink reaches; and the colours of every pixel well inside the circle.
Measured measure(const Picture& p, const shared::SmokeStyle& style, double radius) {
    Measured m;
    const glm::vec3 ink(style.outline);
    const float cx = 0.5f * kWidth, cy = 0.5f * kHeight;
    for (int k = 0; k < 64; ++k) {
        const double angle = 2.0 * std::numbers::pi * (k + 0.5) / 64.0;
        const float dx = float(std::cos(angle)), dy = float(std::sin(angle));
        // The silhouette: walking in from outside, where the coverage first reaches 1/2.
        double edge = -1.0, inkFrom = -1.0;
        for (float r = float(radius) + 10.0f; r > 1.0f && edge < 0.0; r -= 0.05f)
            if (coverage(p, cx + r * dx, cy + r * dy, ink) >= 0.5f) edge = r;
        // The ink: walking out from the centre, the first pixel of its colour.
        for (float r = 1.0f; r < float(edge) && inkFrom < 0.0; r += 0.05f) {
            const uint32_t px = uint32_t(cx + r * dx), py = uint32_t(cy + r * dy);
            const glm::vec3 c(p.at(px, py, 0), p.at(px, py, 1), p.at(px, py, 2));
            if (near(c, ink)) inkFrom = r;
        }
        m.worstRadiusError = std::max(m.worstRadiusError, std::abs(edge - radius));
        m.meanRadius += edge / 64.0;
        if (inkFrom > 0.0) {
            m.narrowestInk = std::min(m.narrowestInk, edge - inkFrom);
            m.widestInk = std::max(m.widestInk, edge - inkFrom);
        } else {
            m.narrowestInk = 0.0;
        }
    }
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const double r = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
            if (r > radius - 1.5) continue;
            std::array<int, 3> key;
            for (int c = 0; c < 3; ++c)
                key[size_t(c)] = int(std::lround(p.at(x, y, c) * 1024.0f));
            ++m.tones[key];
        }
    return m;
}

float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Exactly `bands` + 1 flat colours inside the circle (the bands and the ink), each the default
// ramp's at k / (bands - 1) as the picture's linear light.
void expectTones(const Measured& m, uint32_t bands) {
    std::vector<glm::vec3> expected;
    const auto& ramp = scene::cartoonColours();
    for (uint32_t k = 0; k < bands; ++k) {
        const glm::vec4 c = scene::colourAt(ramp, float(k) / float(bands - 1));
        expected.push_back({srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)});
    }
    std::printf("  %zu distinct colours inside the circle:", m.tones.size());
    for (const auto& [colour, count] : m.tones)
        std::printf(" (%.3f %.3f %.3f) x%d", colour[0] / 1024.0, colour[1] / 1024.0,
                    colour[2] / 1024.0, count);
    std::printf("\n");
    // Exactly bands + 1 colours (the bands and the ink), each on a real share of the disc.
    EXPECT_EQ(m.tones.size(), size_t(bands) + 1);
    for (const auto& [colour, count] : m.tones)
        EXPECT_GE(count, 50) << "a colour on a few pixels: not a flat band";
    for (const glm::vec3& want : expected) {
        bool found = false;
        for (const auto& [colour, count] : m.tones) {
            const glm::vec3 got(colour[0] / 1024.0f, colour[1] / 1024.0f, colour[2] / 1024.0f);
            found = found || glm::all(glm::lessThan(glm::abs(got - want), glm::vec3(2e-3f)));
        }
        EXPECT_TRUE(found) << "no band of colour " << want.r << " " << want.g << " " << want.b;
    }
}

void checkBall(gpu::Context& ctx, const render::SmokePass::Volume& volume, render::SmokeMarch march,
               const std::string& name) {
    const scene::CartoonSmoke& cartoon = volume.shading.cartoon;
    const double radius = analyticRadius(cartoon.threshold);
    const Picture picture = shoot(ctx, volume, march, name + ".png");
    shared::SmokeStyle style{};
    // The ink as drawn: the darkest colour inside the circle's centre row.
    glm::vec3 ink(1.0f);
    for (uint32_t x = 0; x < kWidth; ++x) {
        const glm::vec3 c(picture.at(x, kHeight / 2, 0), picture.at(x, kHeight / 2, 1),
                          picture.at(x, kHeight / 2, 2));
        if (c.r + c.g + c.b < ink.r + ink.g + ink.b) ink = c;
    }
    style.outline = glm::vec4(ink, cartoon.outlineWidth);
    const Measured m = measure(picture, style, radius);
    std::printf("%s: silhouette radius %.2f px (analytic %.2f), worst %.2f px off; ink %.2f to "
                "%.2f px wide (outline_width %.1f)\n",
                name.c_str(), m.meanRadius, radius, m.worstRadiusError, m.narrowestInk, m.widestInk,
                double(cartoon.outlineWidth));
    EXPECT_LE(m.worstRadiusError, 1.0);
    EXPECT_GE(m.narrowestInk, cartoon.outlineWidth - 1.0);
    EXPECT_LE(m.widestInk, cartoon.outlineWidth + 1.0);
    expectTones(m, cartoon.bands);
}

std::unique_ptr<fluid::SmokeSolver> denseBall(gpu::Context& ctx) {
    fluid::SolverOptions options;
    options.grid = {kCells, kCells, kCells, kCell};
    auto solver = fluid::SmokeSolver::create(ctx, options).value();
    solver->setState(ballState(options.grid));
    return solver;
}

glm::vec3 gridOrigin() {
    return kCentre - glm::vec3(0.5f * kCells * kCell);
}

TEST_F(SmokeCartoonTest, ABallShowsItsBandsInkAndCircleByTheFragmentMarch) {
    const auto solver = denseBall(ctx());
    for (uint32_t bands : {2u, 3u, 4u}) {
        const render::SmokePass::Volume volume{solver->pigmentVolume(), solver->options().grid,
                                               gridOrigin(), cartoonShading(bands, 2.0f, 0.25f)};
        checkBall(ctx(), volume, render::SmokeMarch::Fragment,
                  "fragment_bands" + std::to_string(bands));
    }
}

TEST_F(SmokeCartoonTest, ABallShowsItsBandsInkAndCircleByTheComputeMarch) {
    const auto solver = denseBall(ctx());
    const render::SmokePass::Volume volume{solver->pigmentVolume(), solver->options().grid,
                                           gridOrigin(), cartoonShading(3, 4.0f, 0.4f)};
    checkBall(ctx(), volume, render::SmokeMarch::Compute, "compute_outline4");
}

// The keys: defaults, ranges, and each look's keys refused on the other looks in one line.
scene::CartoonSmoke cartoonOf(const std::string& keys) {
    Result<scene::Scene> s = scene::parseScene(
        R"({"effects": [{"type": "smoke", "look": "cartoon")" + keys + "}]}", "test.json");
    EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().message);
    if (!s.ok()) return {};
    const auto* smoke = s.value().effects[0].as<scene::SmokeSpec>();
    EXPECT_TRUE(smoke);
    EXPECT_EQ(smoke->shading.preset, scene::SmokePreset::Cartoon);
    return smoke ? smoke->shading.cartoon : scene::CartoonSmoke{};
}

std::string refusal(const std::string& effect) {
    Result<scene::Scene> s =
        scene::parseScene(R"({"effects": [{"type": "smoke", )" + effect + "}]}", "test.json");
    return s.ok() ? std::string("(accepted)") : s.error().message;
}

TEST(SmokeCartoonKeys, DefaultsAndGivenValuesAreRead) {
    const scene::CartoonSmoke defaults = cartoonOf("");
    EXPECT_EQ(defaults.bands, 3u);
    EXPECT_FLOAT_EQ(defaults.outlineWidth, 2.0f);
    EXPECT_TRUE(defaults.colours.empty()); // the built-in ramp
    const scene::CartoonSmoke given = cartoonOf(
        R"(, "threshold": 0.2, "bands": 4, "outline_width": 3, "rim": 0, "billow": 0.3,
           "billow_scale": 0.5, "billow_speed": 2, "outline_colour": [0, 0, 0.2],
           "colours": [{"at": 0, "colour": [0, 0, 1]}, {"at": 1, "colour": [1, 1, 1]}])");
    EXPECT_FLOAT_EQ(given.threshold, 0.2f);
    EXPECT_EQ(given.bands, 4u);
    EXPECT_FLOAT_EQ(given.outlineWidth, 3.0f);
    EXPECT_FLOAT_EQ(given.rim, 0.0f);
    EXPECT_FLOAT_EQ(given.billow, 0.3f);
    EXPECT_FLOAT_EQ(given.billowScale, 0.5f);
    EXPECT_FLOAT_EQ(given.billowSpeed, 2.0f);
    EXPECT_FLOAT_EQ(given.outlineColour.b, 0.2f);
    ASSERT_EQ(given.colours.size(), 2u);
    EXPECT_FLOAT_EQ(given.colours[0].colour.b, 1.0f);
}

TEST(SmokeCartoonKeys, EachLooksKeysAreRefusedOnTheOthersInOneLine) {
    EXPECT_EQ(refusal(R"("bands": 3)"),
              "test.json: effects[0].bands: only for \"look\": \"cartoon\"");
    EXPECT_EQ(refusal(R"("look": "fire", "threshold": 0.1)"),
              "test.json: effects[0].threshold: only for \"look\": \"cartoon\"");
    const std::string glow = refusal(R"("look": "cartoon", "glow": 2)");
    EXPECT_NE(glow.find("effects[0].glow: not for \"look\": \"cartoon\""), std::string::npos)
        << glow;
    EXPECT_NE(refusal(R"("look": "cartoon", "bands": 5)").find("effects[0].bands"),
              std::string::npos);
    EXPECT_NE(refusal(R"("look": "cartoon", "threshold": 0)").find("effects[0].threshold"),
              std::string::npos);
    EXPECT_NE(refusal(R"("look": "cartoon", "colours": [{"at": 0, "colour": [1, 0, 0]}])")
                  .find("effects[0].colours"),
              std::string::npos);
    EXPECT_NE(refusal(R"("look": "cartoon", "billow": 2)").find("effects[0].billow"),
              std::string::npos);
}

} // namespace
} // namespace mfx::test
