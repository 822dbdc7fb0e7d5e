// The store path (SolverOptions::storePath; docs/fluid.md, "Grid"): every stage, and whole steps,
// stored straight into the field images give the values the buffer-then-copy path gives. The two
// paths run the same arithmetic and differ only in where the result goes, so they must agree bit
// for bit; the buffer path itself is held to the CPU reference by the stage and step tests.
#include "fluid/smoke_solver.h"
#include "tests/fluid_test_util.h"
#include "tests/gpu_test.h"

#include <cstring>
#include <string>
#include <vector>

namespace mfx::test {
namespace {

using fluid::FieldState;
using fluid::SolverOptions;
using fluid::StorePath;

// Values that differ in their bits (NaN never appears here: the inputs are finite).
size_t bitDifferences(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size()) return std::max(a.size(), b.size());
    size_t differ = 0;
    for (size_t i = 0; i < a.size(); ++i)
        differ += std::memcmp(&a[i], &b[i], sizeof(float)) != 0 ? 1 : 0;
    return differ;
}

size_t bitDifferences(const FieldState& a, const FieldState& b) {
    return bitDifferences(a.velocityX, b.velocityX) + bitDifferences(a.velocityY, b.velocityY) +
           bitDifferences(a.velocityZ, b.velocityZ) + bitDifferences(a.pressure, b.pressure) +
           bitDifferences(a.divergence, b.divergence) + bitDifferences(a.pigment, b.pigment);
}

// `options` on one path: the state after `stage` alone (or `steps` whole steps when no stage).
FieldState run(const gpu::Context& ctx, SolverOptions options, StorePath path,
               const FieldState& input, std::optional<fluid::Stage> stage, uint32_t steps) {
    options.storePath = path;
    auto solver = fluid::SmokeSolver::create(ctx, options).value();
    EXPECT_EQ(solver->storesDirect(), path == StorePath::Direct);
    solver->setState(input);
    EXPECT_TRUE(solver->setEmitters(twoEmitters(options.grid)));
    if (stage)
        solver->runStage(*stage);
    else
        for (uint32_t s = 0; s < steps; ++s)
            solver->step();
    return solver->state();
}

struct StoreCase {
    std::string name;
    SolverOptions options;
};

std::vector<StoreCase> storeCases() {
    SolverOptions mixed = mixedBoundaryOptions();
    mixed.vorticity = 2.0f;
    mixed.buoyancy = 1.5f;
    SolverOptions closed = closedBoxOptions();
    closed.vorticity = 1.0f;
    closed.buoyancy = 0.5f;
    SolverOptions half = mixed;
    half.storage = fluid::Storage::Float16;
    SolverOptions maccormack = mixed;
    maccormack.advection = fluid::AdvectionScheme::MacCormack;
    SolverOptions multigrid = closed;
    multigrid.pressureSolver = fluid::PressureSolver::Multigrid;
    return {{"mixed", mixed},
            {"closed", closed},
            {"fp16", half},
            {"maccormack", maccormack},
            {"multigrid", multigrid}};
}

class StorePathTest : public GpuTest, public ::testing::WithParamInterface<StoreCase> {};

TEST_P(StorePathTest, EveryStageStoresTheSameBitsEitherWay) {
    const SolverOptions& options = GetParam().options;
    const FieldState input = randomState(options.grid, 4242);
    for (fluid::Stage stage : fluid::allStages()) {
        const FieldState buffer = run(ctx(), options, StorePath::Buffer, input, stage, 0);
        const FieldState direct = run(ctx(), options, StorePath::Direct, input, stage, 0);
        EXPECT_EQ(bitDifferences(buffer, direct), 0u) << fluid::stageName(stage);
    }
}

TEST_P(StorePathTest, TenStepsStoreTheSameBitsEitherWay) {
    const SolverOptions& options = GetParam().options;
    const FieldState input = randomState(options.grid, 99);
    const FieldState buffer = run(ctx(), options, StorePath::Buffer, input, std::nullopt, 10);
    const FieldState direct = run(ctx(), options, StorePath::Direct, input, std::nullopt, 10);
    EXPECT_EQ(bitDifferences(buffer, direct), 0u);
    // The steps moved something: a comparison of two untouched copies proves nothing.
    EXPECT_GT(bitDifferences(buffer, input), buffer.velocityX.size() / 2);
}

std::string storeCaseName(const ::testing::TestParamInfo<StoreCase>& info) {
    return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Fluid, StorePathTest, ::testing::ValuesIn(storeCases()), storeCaseName);

TEST_F(GpuTest, TheStorePathFollowsTheDeviceUnlessSet) {
    SolverOptions options = closedBoxOptions();
    auto automatic = fluid::SmokeSolver::create(ctx(), options).value();
    EXPECT_EQ(automatic->storesDirect(), !ctx().info().isCpu());
    EXPECT_EQ(fluid::storePathFromName("direct"), StorePath::Direct);
    EXPECT_EQ(std::string(fluid::storePathName(StorePath::Buffer)), "buffer");
    EXPECT_FALSE(fluid::storePathFromName("image").has_value());
}

} // namespace
} // namespace mfx::test
