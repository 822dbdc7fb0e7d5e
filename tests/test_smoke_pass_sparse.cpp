// The smoke pass over a sparse grid (shaders/render/smoke_march.glsl built with
// MFX_SPARSE_PIGMENT): its picture is the dense grid's picture of the same pigment, while its march
// skips the empty bricks.
#include "core/gpu/commands.h"
#include "core/scene/kinds/smoke_effect.h"
#include "core/scene/scene.h"
#include "fluid/smoke_solver.h"
#include "fluid/sparse_smoke_solver.h"
#include "render/image_output.h"
#include "render/smoke_pass.h"
#include "tests/gpu_test.h"

#include <algorithm>
#include <cmath>

namespace mfx::test {
namespace {

using SparseSmokePassTest = GpuTest;

constexpr uint32_t kWidth = 160, kHeight = 120;
const fluid::GridShape kDomain{48, 24, 24, 0.05f}; // 6 x 3 x 3 bricks

// Two balls of pigment, of different colours, far apart along x: bricks with nothing between
// and around them, which the sparse march must skip without changing the picture.
fluid::FieldState twoBalls() {
    fluid::FieldState state = fluid::FieldState::zero(kDomain);
    const glm::vec3 centres[2] = {{9.0f, 11.0f, 12.0f}, {38.0f, 13.0f, 11.0f}};
    const glm::vec3 colours[2] = {{1.0f, 0.5f, 0.2f}, {0.3f, 0.6f, 1.0f}};
    for (uint32_t z = 0; z < kDomain.cellsZ; ++z)
        for (uint32_t y = 0; y < kDomain.cellsY; ++y)
            for (uint32_t x = 0; x < kDomain.cellsX; ++x)
                for (int b = 0; b < 2; ++b) {
                    const float d = glm::length(glm::vec3(x, y, z) + 0.5f - centres[b]);
                    const float a = glm::clamp(1.5f * (1.0f - d / 6.0f), 0.0f, 1.0f);
                    if (a <= 0.0f) continue;
                    const size_t i = kDomain.index(x, y, z) * 4;
                    for (int c = 0; c < 3; ++c)
                        state.pigment[i + size_t(c)] = colours[b][c] * a;
                    state.pigment[i + 3] = a;
                }
    return state;
}

struct Picture {
    std::vector<uint8_t> rgba;
};

// The volume alone over a dark background (no scene: the depth is the far plane), from a camera
// looking along the row of bricks at a slant, so most rays cross empty bricks.
Picture shoot(gpu::Context& ctx, const render::SmokePass::Volume& volume, const std::string& png,
              const render::SmokeLook& look = {}) {
    scene::CameraSpec cameraSpec;
    cameraSpec.position = glm::vec3(-0.6f, 1.3f, 2.2f);
    cameraSpec.target = glm::vec3(1.2f, 0.6f, 0.6f);
    const render::SceneCamera camera = render::makeCamera(cameraSpec, float(kWidth) / kHeight);
    render::RenderTarget target = render::createRenderTarget(ctx, kWidth, kHeight);
    render::SmokePass smokePass(ctx);
    scene::LightSpec key;
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        render::beginRendering(cmd, target, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        render::endRendering(cmd);
        smokePass.draw(cmd, target, std::span(&volume, 1), camera, key, look);
    });
    Picture picture{render::readColor(ctx, target)};
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/smoke_pass_sparse";
    EXPECT_TRUE(render::ensureOutputDirectory(dir).ok());
    EXPECT_TRUE(render::writePng(dir + "/" + png, kWidth, kHeight, picture.rgba).ok());
    return picture;
}

// Stores the bricks of `state` that hold pigment (all of them with `everyBrick`).
std::unique_ptr<fluid::SparseSmokeSolver>
sparseOf(gpu::Context& ctx, const fluid::FieldState& state, bool everyBrick) {
    fluid::SolverOptions options;
    options.grid = kDomain;
    auto sparse = fluid::SparseSmokeSolver::create(ctx, options, 64, 8);
    EXPECT_TRUE(sparse.ok()) << (sparse.ok() ? "" : sparse.error().message);
    if (!sparse.ok()) return nullptr;
    fluid::SparseBricks& layout = sparse.value()->layout();
    layout.clearWanted();
    for (uint32_t z = 0; z < kDomain.cellsZ; ++z)
        for (uint32_t y = 0; y < kDomain.cellsY; ++y)
            for (uint32_t x = 0; x < kDomain.cellsX; ++x)
                if (everyBrick || state.pigment[kDomain.index(x, y, z) * 4 + 3] > 0.0f)
                    layout.wantCell(glm::ivec3(x, y, z));
    sparse.value()->commitActive();
    sparse.value()->setState(state);
    return std::move(sparse).value();
}

// Channels (0-255) where two pictures differ by more than `tolerance`, and the largest difference.
std::pair<size_t, int> compare(const Picture& a, const Picture& b, int tolerance) {
    size_t over = 0;
    int largest = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) {
        const int d = std::abs(int(a.rgba[i]) - int(b.rgba[i]));
        largest = std::max(largest, d);
        over += d > tolerance ? 1 : 0;
    }
    return {over, largest};
}

// Pixels brighter than the black background by more than 30 in some channel: smoke.
size_t smokyPixels(const Picture& p) {
    size_t n = 0;
    for (size_t i = 0; i < p.rgba.size(); i += 4)
        n += std::max({p.rgba[i], p.rgba[i + 1], p.rgba[i + 2]}) > 30 ? 1 : 0;
    return n;
}

// The sparse march samples trilinearly by hand in fp32; the dense one through the image sampler,
// whose weights a GPU may round (8 bits of sub-texel precision is common): a level or two of 255
// apart after the march's exponentials and the sRGB encoding. 3 levels, and no more than that.
constexpr int kTolerance = 3;

TEST_F(SparseSmokePassTest, TheSparseMarchDrawsWhatTheDenseMarchDrawsOfTheSamePigment) {
    const fluid::FieldState state = twoBalls();
    fluid::SolverOptions options;
    options.grid = kDomain;
    auto dense = fluid::SmokeSolver::create(ctx(), options).value();
    dense->setState(state);
    const auto some = sparseOf(ctx(), state, false);
    const auto every = sparseOf(ctx(), state, true);
    ASSERT_TRUE(some && every);
    // The balls' bricks only: fewer than half the domain's 54.
    EXPECT_LT(some->activeBricks().size(), 27u);
    EXPECT_EQ(every->activeBricks().size(), 54u);
    const glm::vec3 origin(0.0f);
    const Picture d = shoot(ctx(), {dense->pigmentVolume(), kDomain, origin, {}}, "dense.png");
    const Picture s = shoot(ctx(), {some->pigmentVolume(), kDomain, origin, {}}, "sparse.png");
    const Picture e = shoot(ctx(), {every->pigmentVolume(), kDomain, origin, {}}, "every.png");
    EXPECT_GT(smokyPixels(d), 500u);
    const auto [someOver, someLargest] = compare(s, d, kTolerance);
    EXPECT_EQ(someOver, 0u) << "largest difference " << someLargest;
    const auto [everyOver, everyLargest] = compare(e, d, kTolerance);
    EXPECT_EQ(everyOver, 0u) << "largest difference " << everyLargest;
    // Skipping is exact: the same atlas values with and without empty bricks give one picture.
    const auto [skipOver, skipLargest] = compare(s, e, 0);
    EXPECT_EQ(skipOver, 0u) << "largest difference " << skipLargest;
}

// The sparse atlas's compute march (a GPU's) draws what its fragment march draws, skipping the
// same empty bricks.
TEST_F(SparseSmokePassTest, TheComputeMarchDrawsWhatTheFragmentMarchDraws) {
    const auto some = sparseOf(ctx(), twoBalls(), false);
    ASSERT_TRUE(some);
    render::SmokeLook fragment, compute;
    fragment.march = render::SmokeMarch::Fragment;
    compute.march = render::SmokeMarch::Compute;
    const render::SmokePass::Volume volume{some->pigmentVolume(), kDomain, glm::vec3(0.0f), {}};
    const Picture f = shoot(ctx(), volume, "fragment_march.png", fragment);
    const Picture c = shoot(ctx(), volume, "compute_march.png", compute);
    EXPECT_GT(smokyPixels(f), 500u);
    const auto [over, largest] = compare(c, f, 1);
    EXPECT_EQ(over, 0u) << "largest difference " << largest;
}

// The cartoon look (shaders/render/smoke_cartoon.glsl) over the sparse atlas draws the dense
// grid's surface, by both marches. Its tones are flat and its edges hard, so where the two
// samplers' rounding (above) puts a pixel's light or margin on the other side of a band's edge or
// the silhouette, that pixel differs by a whole band: such pixels are counted and must be few
// (under 1% of the smoke's); all others agree within kTolerance.
TEST_F(SparseSmokePassTest, TheCartoonLookDrawsTheDenseSurfaceOverTheSparseAtlas) {
    const fluid::FieldState state = twoBalls();
    fluid::SolverOptions options;
    options.grid = kDomain;
    auto dense = fluid::SmokeSolver::create(ctx(), options).value();
    dense->setState(state);
    const auto some = sparseOf(ctx(), state, false);
    ASSERT_TRUE(some);
    scene::SmokeShading cartoon = scene::smokeShading(scene::SmokePreset::Cartoon);
    cartoon.cartoon.threshold = 0.3f;
    for (render::SmokeMarch march : {render::SmokeMarch::Fragment, render::SmokeMarch::Compute}) {
        render::SmokeLook look;
        look.march = march;
        const std::string name = march == render::SmokeMarch::Fragment ? "fragment" : "compute";
        const Picture d = shoot(ctx(), {dense->pigmentVolume(), kDomain, glm::vec3(0.0f), cartoon},
                                "cartoon_dense_" + name + ".png", look);
        const Picture s = shoot(ctx(), {some->pigmentVolume(), kDomain, glm::vec3(0.0f), cartoon},
                                "cartoon_sparse_" + name + ".png", look);
        const size_t smoky = smokyPixels(d);
        size_t differing = 0;
        for (size_t i = 0; i < d.rgba.size(); i += 4) {
            int worst = 0;
            for (size_t c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(int(d.rgba[i + c]) - int(s.rgba[i + c])));
            differing += worst > kTolerance ? 1 : 0;
        }
        std::printf("cartoon, %s march: %zu smoky pixels, %zu differ by more than %d\n",
                    name.c_str(), smoky, differing, kTolerance);
        EXPECT_GT(smoky, 500u);
        EXPECT_LT(double(differing), 0.01 * double(smoky));
    }
}

TEST_F(SparseSmokePassTest, ASparseGridWithNoActiveBrickDrawsNothing) {
    fluid::SolverOptions options;
    options.grid = kDomain;
    auto sparse = fluid::SparseSmokeSolver::create(ctx(), options, 64, 8).value();
    const Picture empty =
        shoot(ctx(), {sparse->pigmentVolume(), kDomain, glm::vec3(0.0f), {}}, "empty.png");
    EXPECT_EQ(smokyPixels(empty), 0u);
}

} // namespace
} // namespace mfx::test
