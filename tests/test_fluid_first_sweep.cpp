// A cold Jacobi solve's first sweep done by the divergence pass (SolverOptions::
// firstSweepInDivergence; shaders/fluid/compute_divergence.comp): with every pressure 0 the sweep
// needs each cell's own divergence only, so the step can compute it beside the divergence and
// start the solve at its second sweep. The arithmetic is the sweep's, operation for operation, so
// whole steps must give the same fields as the solve's own first sweep; the solve itself is held
// to the CPU reference by the stage and step tests.
#include "fluid/smoke_solver.h"
#include "tests/fluid_test_util.h"
#include "tests/gpu_test.h"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

namespace mfx::test {
namespace {

using fluid::ByDevice;
using fluid::FieldState;
using fluid::SolverOptions;

struct StepsRun {
    FieldState state;
    fluid::StageDispatches dispatches; // of the last step
};

StepsRun run(const gpu::Context& ctx, SolverOptions options, ByDevice firstSweep,
             const FieldState& input, uint32_t steps) {
    options.firstSweepInDivergence = firstSweep;
    auto solver = fluid::SmokeSolver::create(ctx, options).value();
    solver->setState(input);
    EXPECT_TRUE(solver->setEmitters(twoEmitters(options.grid)));
    for (uint32_t s = 0; s < steps; ++s)
        solver->step();
    return {solver->state(), solver->lastStepDispatches()};
}

// The largest |a - b| over every field (a -0 where the other gives +0 counts as equal).
float largestDifference(const FieldState& a, const FieldState& b) {
    float largest = 0.0f;
    auto compare = [&](const std::vector<float>& x, const std::vector<float>& y) {
        EXPECT_EQ(x.size(), y.size());
        for (size_t i = 0; i < std::min(x.size(), y.size()); ++i)
            largest = std::max(largest, std::abs(x[i] - y[i]));
    };
    compare(a.velocityX, b.velocityX);
    compare(a.velocityY, b.velocityY);
    compare(a.velocityZ, b.velocityZ);
    compare(a.pressure, b.pressure);
    compare(a.divergence, b.divergence);
    compare(a.pigment, b.pigment);
    return largest;
}

uint32_t dispatchesOf(const fluid::StageDispatches& list, const char* stage) {
    for (const auto& [name, count] : list)
        if (name == stage) return count;
    return 0;
}

struct SweepCase {
    std::string name;
    SolverOptions options;
};

std::vector<SweepCase> sweepCases() {
    const fluid::GridShape odd{9, 7, 6, 0.125f}; // rows padded to whole vec4s
    SolverOptions walls = pressureOptions(odd, Boundaries::Walls, fluid::PressureSolver::Jacobi);
    SolverOptions open = pressureOptions(odd, Boundaries::Open, fluid::PressureSolver::Jacobi);
    SolverOptions periodic =
        pressureOptions(odd, Boundaries::Periodic, fluid::PressureSolver::Jacobi);
    SolverOptions mixed = mixedBoundaryOptions();
    mixed.warmStart = false;
    SolverOptions half = mixed;
    half.storage = fluid::Storage::Float16;
    SolverOptions oneSweep = mixed; // the first sweep is the last: it writes the pressure image
    oneSweep.jacobiIterations = 1;
    SolverOptions oneSweepDirect = oneSweep; // ... beside the divergence stored into its image
    oneSweepDirect.storePath = fluid::StorePath::Direct;
    SolverOptions direct = closedBoxOptions();
    direct.storePath = fluid::StorePath::Direct;
    SolverOptions buffer = closedBoxOptions();
    buffer.storePath = fluid::StorePath::Buffer;
    SolverOptions substeps = mixed;
    substeps.substeps = 2;
    return {{"walls", walls},         {"open", open},
            {"periodic", periodic},   {"mixed", mixed},
            {"fp16", half},           {"one_sweep", oneSweep},
            {"direct_store", direct}, {"buffer_store", buffer},
            {"substeps", substeps},   {"one_sweep_direct", oneSweepDirect}};
}

void PrintTo(const SweepCase& c, std::ostream* out) {
    *out << c.name;
}

class FirstSweepTest : public GpuTest, public ::testing::WithParamInterface<SweepCase> {};

TEST_P(FirstSweepTest, StepsGiveTheSameFieldsWithTheSweepInTheDivergencePass) {
    const SolverOptions& options = GetParam().options;
    const FieldState input = randomState(options.grid, 2718);
    const StepsRun apart = run(ctx(), options, ByDevice::Off, input, 6);
    const StepsRun fused = run(ctx(), options, ByDevice::On, input, 6);
    EXPECT_EQ(largestDifference(apart.state, fused.state), 0.0f);
    // The solve moved the pressure: two solves that did nothing would agree too.
    float pressureMoved = 0.0f;
    for (size_t i = 0; i < input.pressure.size(); ++i)
        pressureMoved =
            std::max(pressureMoved, std::abs(fused.state.pressure[i] - input.pressure[i]));
    EXPECT_GT(pressureMoved, 1e-3f);

    // One solve_pressure dispatch fewer per sub-step, and no more anywhere else.
    const uint32_t substeps = options.substeps;
    EXPECT_EQ(dispatchesOf(fused.dispatches, "solve_pressure") + substeps,
              dispatchesOf(apart.dispatches, "solve_pressure"));
    EXPECT_EQ(dispatchesOf(fused.dispatches, "compute_divergence"),
              dispatchesOf(apart.dispatches, "compute_divergence"));
}

std::string sweepCaseName(const ::testing::TestParamInfo<SweepCase>& info) {
    return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Fluid, FirstSweepTest, ::testing::ValuesIn(sweepCases()), sweepCaseName);

// Run alone, the divergence stage writes the divergence only: the pressure stays as it was.
TEST_F(GpuTest, TheDivergenceStageAloneLeavesThePressure) {
    SolverOptions options = mixedBoundaryOptions();
    options.warmStart = false;
    options.firstSweepInDivergence = ByDevice::On;
    const FieldState input = randomState(options.grid, 31);
    auto solver = fluid::SmokeSolver::create(ctx(), options).value();
    solver->setState(input);
    solver->runStage(fluid::Stage::ComputeDivergence);
    const FieldState after = solver->state();
    EXPECT_EQ(after.pressure, input.pressure);
    EXPECT_NE(after.divergence, input.divergence);
    // And the pressure stage alone still runs every sweep.
    solver->runStage(fluid::Stage::SolvePressure);
    options.firstSweepInDivergence = ByDevice::Off;
    auto apart = fluid::SmokeSolver::create(ctx(), options).value();
    apart->setState(after);
    apart->runStage(fluid::Stage::SolvePressure);
    EXPECT_EQ(largestDifference(solver->state(), apart->state()), 0.0f);
}

// Where the solve does not start cold, or is not Jacobi, nothing moves into the divergence pass.
TEST(FirstSweepOptions, OnlyAColdJacobiSolveFusesItsFirstSweep) {
    SolverOptions o;
    EXPECT_TRUE(o.firstSweepFused()); // the default: a cold Jacobi solve, on every device
    o.firstSweepInDivergence = ByDevice::Off;
    EXPECT_FALSE(o.firstSweepFused());
    o.firstSweepInDivergence = ByDevice::Auto;
    o.warmStart = true;
    EXPECT_FALSE(o.firstSweepFused());
    o.warmStart = false;
    o.jacobiIterations = 0;
    EXPECT_FALSE(o.firstSweepFused());
    o.jacobiIterations = 20;
    o.pressureSolver = fluid::PressureSolver::RedBlackGaussSeidel;
    EXPECT_FALSE(o.firstSweepFused());
}

} // namespace
} // namespace mfx::test
