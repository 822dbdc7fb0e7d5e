// Moving solids under hard settings (docs/fluid.md, "Solids"): 2,000 whole GPU steps on a small
// grid, dense and sparse, with the usual emitters (tests/fluid_stability_util.h) and a solid that
// fills most of the grid, moves at CFL 5, touches the domain's edges, or appears and vanishes every
// other step; under a closed box and under mixed boundaries. Read back at step 1 and every 100
// steps and held to the stability tests' bounds (tests/test_fluid_stability.cpp): no NaN or Inf;
// pigment within [0, the emitters' largest] and none inside a solid; kinetic energy below the
// ceiling of every energy-carrying face at the fastest speed present, the solids' speeds counted
// with the emitters' (a solid face is set to its solid's velocity, and every other stage but the
// projection keeps |u_c| within the fastest such value; the projection never adds energy).
#include "core/gpu/commands.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/smoke_solver.h"
#include "fluid/sparse_smoke_solver.h"
#include "tests/fluid_stability_util.h"
#include "tests/gpu_test.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <span>
#include <string>

namespace mfx::test {
namespace {

using stability::Boundaries;

constexpr fluid::GridShape kGrid{12, 9, 8, 1.0f / 12.0f}; // 1 x 0.75 x 0.67 world units
constexpr uint32_t kSteps = 2000;
constexpr uint32_t kCheckEvery = 100;

shared::FluidSolid capsule(glm::vec3 a, glm::vec3 b, float radius, glm::vec3 velocityA,
                           glm::vec3 velocityB) {
    return {glm::vec4(a, radius), glm::vec4(b, 0.0f), glm::vec4(velocityA, 0.0f),
            glm::vec4(velocityB, 0.0f)};
}

shared::FluidSolid sphere(glm::vec3 centre, float radius, glm::vec3 velocity) {
    return capsule(centre, centre, radius, velocity, velocity);
}

// A case: the solids of each step (where step s ends, s counted from 0).
struct SolidCase {
    const char* name;
    std::function<std::vector<shared::FluidSolid>(uint32_t step, float dt)> solids;
};

std::vector<SolidCase> solidCases(const fluid::GridShape& grid = kGrid) {
    const glm::vec3 size = glm::vec3(grid.cellsX, grid.cellsY, grid.cellsZ) * grid.cellSize;
    const float h = grid.cellSize;
    return {
        // A sphere larger than the box across y and z, rocking along x.
        {"FillsMostOfTheGrid",
         [size](uint32_t step, float dt) {
             const float t = float(step + 1) * dt;
             const glm::vec3 centre = 0.5f * size + glm::vec3(0.06f * std::sin(6.0f * t), 0, 0);
             const glm::vec3 velocity(0.36f * std::cos(6.0f * t), 0.0f, 0.0f);
             return std::vector{sphere(centre, 0.52f, velocity)};
         }},
        // A sphere crossing the box diagonally at five cells a step, wrapping round to the far
        // side when it leaves.
        {"MovesAtCfl5",
         [size, h](uint32_t step, float dt) {
             const glm::vec3 velocity =
                 glm::normalize(glm::vec3(1.0f, 0.6f, 0.4f)) * (5.0f * h / dt);
             glm::vec3 centre = 0.3f * size + velocity * (float(step + 1) * dt);
             centre -= size * glm::floor(centre / size);
             return std::vector{sphere(centre, 0.15f, velocity)};
         }},
        // A sphere centred on the -x face, a capsule through the +y face and one along the -z
        // face's edge, each moving a little.
        {"TouchesTheEdges",
         [size](uint32_t step, float dt) {
             const float t = float(step + 1) * dt;
             const float wave = 0.1f * std::sin(4.0f * t), speed = 0.4f * std::cos(4.0f * t);
             return std::vector{
                 sphere({0.0f, 0.5f * size.y + wave, 0.5f * size.z}, 0.2f, {0.0f, speed, 0.0f}),
                 capsule({0.7f * size.x, 0.8f * size.y, 0.5f * size.z},
                         {0.7f * size.x + wave, 1.2f * size.y, 0.5f * size.z}, 0.1f,
                         {0.0f, 0.0f, 0.0f}, {speed, 0.0f, 0.0f}),
                 capsule({0.2f * size.x, 0.2f * size.y, 0.0f}, {0.8f * size.x, 0.2f * size.y, 0.0f},
                         0.12f, {0.0f, 0.0f, speed}, {0.0f, 0.0f, speed})};
         }},
        // A fast sphere present on even steps and gone on odd ones.
        {"AppearsAndVanishes",
         [size](uint32_t step, float) {
             if (step % 2 == 1) return std::vector<shared::FluidSolid>{};
             return std::vector{sphere(0.5f * size, 0.25f, {3.0f, -2.0f, 1.0f})};
         }},
    };
}

// The energy of every energy-carrying face of component c at the fastest |velocity_c| of the
// emitters, the solids of any step and the start (at rest).
double energyCeiling(const fluid::SolverOptions& o,
                     const std::vector<shared::FluidEmitter>& emitters, const SolidCase& c) {
    glm::dvec3 top(0.0);
    for (const shared::FluidEmitter& e : emitters)
        top = glm::max(top, glm::abs(glm::dvec3(glm::vec3(e.velocityStrength))));
    for (uint32_t step = 0; step < kSteps; ++step)
        for (const shared::FluidSolid& s : c.solids(step, o.dt))
            top = glm::max(top, glm::max(glm::abs(glm::dvec3(glm::vec3(s.velocityA))),
                                         glm::abs(glm::dvec3(glm::vec3(s.velocityB)))));
    const double h = double(o.grid.cellSize);
    double ceiling = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
        const glm::uvec3 n = fluid::faceExtent(o.grid, axis);
        auto wall = [&](int face) {
            const fluid::Boundary k = o.boundaries[size_t(face)].kind;
            return k == fluid::Boundary::WallFreeSlip || k == fluid::Boundary::WallNoSlip;
        };
        uint64_t along = n[axis];
        if (o.periodic(axis))
            along -= 1;
        else
            along -= (wall(2 * axis) ? 1 : 0) + (wall(2 * axis + 1) ? 1 : 0);
        const double faces = double(along) * double(uint64_t(n.x) * n.y * n.z / n[axis]);
        ceiling += 0.5 * top[axis] * top[axis] * faces * h * h * h;
    }
    return ceiling;
}

struct HardCase {
    size_t solidCase;
    Boundaries boundaries;
};

// A solver under test: its solids for the next step, a step recorded (after its rebuild, on the
// sparse domain), and its fields.
struct HardCaseSolver {
    std::function<Status(std::span<const shared::FluidSolid>)> setSolids;
    std::function<void(VkCommandBuffer)> recordStep;
    std::function<fluid::FieldState()> state;
};

// 2,000 steps of case `c` with the usual emitters, checked at step 1 and every 100 steps.
void runHardCase(const gpu::Context& ctx, const fluid::SolverOptions& options, const SolidCase& c,
                 const HardCaseSolver& solver) {
    const fluid::GridShape& grid = options.grid;
    const auto emitters = stability::usualEmitters(grid, 1.0f);
    const double ceiling = energyCeiling(options, emitters, c);
    double pigmentCeiling = 0.0;
    for (const shared::FluidEmitter& e : emitters)
        for (int channel = 0; channel < 4; ++channel)
            pigmentCeiling = std::max(pigmentCeiling, double(e.pigment[channel]));
    fluid::ReferenceSolver marks(options); // the solid cells, as the GPU marks them
    double largestEnergy = 0.0, largestSolidShare = 0.0;
    uint32_t done = 0;
    std::vector<uint32_t> checkpoints = {1};
    for (uint32_t s = kCheckEvery; s <= kSteps; s += kCheckEvery)
        checkpoints.push_back(s);
    for (uint32_t checkpoint : checkpoints) {
        // The steps up to the checkpoint, at most kStepsPerSubmit to a command buffer, each with
        // its own solids (markSolids copies them into the recording).
        while (done < checkpoint) {
            const uint32_t batch = std::min(stability::kStepsPerSubmit, checkpoint - done);
            gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
                for (uint32_t i = 0; i < batch; ++i) {
                    ASSERT_TRUE(solver.setSolids(c.solids(done + i, options.dt)).ok());
                    solver.recordStep(cmd);
                }
            });
            if (::testing::Test::HasFatalFailure()) return;
            done += batch;
        }
        const std::vector<shared::FluidSolid> solids = c.solids(done - 1, options.dt);
        marks.setSolids(solids);
        const fluid::FieldState state = solver.state();
        const fluid::Diagnostics d = fluid::computeDiagnostics(options, state);
        ASSERT_EQ(d.nonFinite, 0u) << "step " << done;
        double low = 0.0, inside = 0.0;
        size_t solidCells = 0;
        for (int k = 0; k < int(grid.cellsZ); ++k)
            for (int j = 0; j < int(grid.cellsY); ++j)
                for (int i = 0; i < int(grid.cellsX); ++i) {
                    const bool solid = marks.solidCell({i, j, k});
                    solidCells += solid ? 1 : 0;
                    for (int channel = 0; channel < 4; ++channel) {
                        const double p = state.pigment[grid.index(i, j, k) * 4 + size_t(channel)];
                        low = std::min(low, p);
                        if (solid) inside += std::abs(p);
                    }
                }
        EXPECT_GE(low, -1e-5 * pigmentCeiling) << "step " << done;
        EXPECT_LE(d.maxPigment, pigmentCeiling * (1.0 + 1e-5)) << "step " << done;
        EXPECT_EQ(inside, 0.0) << "pigment inside a solid, step " << done;
        EXPECT_LE(d.kineticEnergy, ceiling) << "step " << done;
        largestEnergy = std::max(largestEnergy, d.kineticEnergy);
        largestSolidShare =
            std::max(largestSolidShare, double(solidCells) / double(grid.cellCount()));
    }
    const fluid::Diagnostics last = fluid::computeDiagnostics(options, solver.state());
    std::printf("%s: largest energy %.3g of the ceiling %.3g (%.0f%%), solid cells up to %.0f%%, "
                "pigment %.3g at the end\n",
                c.name, largestEnergy, ceiling, 100.0 * largestEnergy / ceiling,
                100.0 * largestSolidShare, last.totalPigment.w);
    EXPECT_GT(last.totalPigment.w, 0.0) << "the emitters put pigment in";
    if (std::string(c.name) == "FillsMostOfTheGrid") {
        EXPECT_GT(largestSolidShare, 0.5);
    }
}

class GpuSolidsHardCaseTest : public GpuTest, public ::testing::WithParamInterface<HardCase> {};

TEST_P(GpuSolidsHardCaseTest, StaysFiniteAndBoundedFor2000Steps) {
    const SolidCase c = solidCases()[GetParam().solidCase];
    const fluid::SolverOptions options = stability::usualOptions(kGrid, GetParam().boundaries);
    auto created = fluid::SmokeSolver::create(ctx(), options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    fluid::SmokeSolver& gpu = *created.value();
    ASSERT_TRUE(gpu.setEmitters(stability::usualEmitters(kGrid, 1.0f)).ok());
    runHardCase(ctx(), options, c,
                {[&](std::span<const shared::FluidSolid> s) { return gpu.setSolids(s); },
                 [&](VkCommandBuffer cmd) { gpu.recordStep(cmd); }, [&] { return gpu.state(); }});
}

// The same on the sparse domain (2 x 2 x 1 bricks of 8³ cells), its active set rebuilt on the GPU
// before every step as a scene's grid rebuilds it (the solids' bricks wanted, so a solid that
// appears and vanishes makes bricks come and go): closed, and open along x instead of the mixed
// boxes' periodic x (the sparse domain has no periodic axis).
class SparseSolidsHardCaseTest : public GpuTest, public ::testing::WithParamInterface<HardCase> {};

TEST_P(SparseSolidsHardCaseTest, StaysFiniteAndBoundedFor2000Steps) {
    constexpr fluid::GridShape kSparseGrid{16, 16, 8, 1.0f / 16.0f}; // 1 x 1 x 0.5 world units
    const SolidCase c = solidCases(kSparseGrid)[GetParam().solidCase];
    fluid::SolverOptions options = stability::usualOptions(kSparseGrid, GetParam().boundaries);
    if (options.periodic(0)) {
        options.boundaries[fluid::FaceLowX].kind = fluid::Boundary::Open;
        options.boundaries[fluid::FaceHighX].kind = fluid::Boundary::Open;
    }
    auto created = fluid::SparseSmokeSolver::create(ctx(), options, 4, 4);
    ASSERT_TRUE(created.ok()) << created.error().message;
    fluid::SparseSmokeSolver& gpu = *created.value();
    ASSERT_TRUE(gpu.setEmitters(stability::usualEmitters(kSparseGrid, 1.0f)).ok());
    const float speed = 1e-4f * options.grid.cellSize / options.dt;
    runHardCase(ctx(), options, c,
                {[&](std::span<const shared::FluidSolid> s) { return gpu.setSolids(s); },
                 [&](VkCommandBuffer cmd) {
                     gpu.recordRebuild(cmd, 1e-4f, speed, fluid::kBrickSize);
                     gpu.recordStep(cmd);
                 },
                 [&] { return gpu.state(); }});
    EXPECT_EQ(gpu.lastSharedFaceMismatches(), 0u);
}

std::vector<HardCase> hardCases() {
    std::vector<HardCase> cases;
    for (size_t i = 0; i < solidCases().size(); ++i)
        for (Boundaries b : {Boundaries::Closed, Boundaries::Mixed})
            cases.push_back({i, b});
    return cases;
}

std::string hardCaseName(const ::testing::TestParamInfo<HardCase>& param) {
    return std::string(solidCases()[param.param.solidCase].name) +
           (param.param.boundaries == Boundaries::Closed ? "_Closed" : "_Mixed");
}

INSTANTIATE_TEST_SUITE_P(SparseSolids, SparseSolidsHardCaseTest, ::testing::ValuesIn(hardCases()),
                         hardCaseName);

INSTANTIATE_TEST_SUITE_P(GpuSolids, GpuSolidsHardCaseTest, ::testing::ValuesIn(hardCases()),
                         hardCaseName);

} // namespace
} // namespace mfx::test
