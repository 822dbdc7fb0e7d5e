// The limited MacCormack and BFECC advection on the GPU (shaders/fluid/advect_velocity.comp and
// advect_pigment.comp, in passes) against the CPU reference (fluid/reference/maccormack.cpp,
// bfecc.cpp): each advection stage alone from the same random input, relative L2 at most 1e-5 as
// for every stage (fp32 against fp64); 100 whole steps of a scenario within the whole-step bound;
// and the maximum principle kept by the GPU's own pigment.
#include "fluid/field_compare.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/scenarios.h"
#include "fluid/smoke_solver.h"
#include "tests/fluid_side_by_side.h"
#include "tests/fluid_test_util.h"
#include "tests/gpu_test.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace mfx::test {
namespace {

struct AdvectionCase {
    AdvectionScheme scheme;
    fluid::Stage stage;
    bool mixedBoundaries; // mixed: every boundary kind and RK2 back-tracing; closed: Euler
};

std::string caseName(const ::testing::TestParamInfo<AdvectionCase>& info) {
    std::string name = std::string(fluid::advectionName(info.param.scheme)) + "_" +
                       fluid::stageName(info.param.stage) +
                       (info.param.mixedBoundaries ? "_mixed" : "_closed");
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

class GpuAdvectionStageTest : public GpuTest,
                              public ::testing::WithParamInterface<AdvectionCase> {};

TEST_P(GpuAdvectionStageTest, GpuMatchesReference) {
    const AdvectionCase c = GetParam();
    SolverOptions options = c.mixedBoundaries ? mixedBoundaryOptions() : closedBoxOptions();
    options.advection = c.scheme;
    const FieldState input = randomState(options.grid, 4321);

    auto created = fluid::SmokeSolver::create(ctx(), options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    fluid::SmokeSolver& gpu = *created.value();
    gpu.setState(input);
    gpu.runStage(c.stage);
    fluid::ReferenceSolver cpu(options);
    cpu.setState(input);
    cpu.runStage(c.stage, {});

    const FieldState cpuState = cpu.state();
    const fluid::StateDifference d = fluid::difference(gpu.state(), cpuState);
    EXPECT_LE(d.velocity.relL2, 1e-5) << "velocity (max abs " << d.velocity.maxAbs << ")";
    EXPECT_LE(d.pigment.relL2, 1e-5) << "pigment (max abs " << d.pigment.maxAbs << ")";
    // The corrected scheme differs from semi-Lagrangian advection of the same input (guards
    // against a scheme that silently fell back to it).
    SolverOptions plain = options;
    plain.advection = AdvectionScheme::SemiLagrangian;
    fluid::ReferenceSolver semiLagrangian(plain);
    semiLagrangian.setState(input);
    semiLagrangian.runStage(c.stage, {});
    EXPECT_GT(fluid::difference(cpuState, semiLagrangian.state()).maxRelL2(), 1e-3)
        << "the scheme gave what semi-Lagrangian advection gives";
}

std::vector<AdvectionCase> advectionCases() {
    std::vector<AdvectionCase> cases;
    for (AdvectionScheme scheme : {AdvectionScheme::MacCormack, AdvectionScheme::Bfecc})
        for (fluid::Stage stage : {fluid::Stage::AdvectVelocity, fluid::Stage::AdvectPigment})
            for (bool mixed : {false, true})
                cases.push_back({scheme, stage, mixed});
    return cases;
}

INSTANTIATE_TEST_SUITE_P(GpuAdvection, GpuAdvectionStageTest, ::testing::ValuesIn(advectionCases()),
                         caseName);

// 100 steps of the puff at 16^3 with each corrected scheme, GPU against the reference from the same
// start, within test_fluid_steps.cpp's whole-step bound of 1e-4 (fp32 against fp64, the rounding
// of every stage accumulated over 100 steps).
class GpuAdvectionStepsTest : public GpuTest,
                              public ::testing::WithParamInterface<AdvectionScheme> {};

TEST_P(GpuAdvectionStepsTest, HundredStepsStayCloseToReference) {
    SideBySide run;
    runSideBySide(
        ctx(), "puff", {16, 16, 16}, 100, [&](SolverOptions& o) { o.advection = GetParam(); }, run);
    if (HasFatalFailure()) return;
    printDifference(fluid::advectionName(GetParam()), run.difference);
    expectClose(run.difference, 1e-4, "100 steps");
    expectMovingAndFinite(run);
}

// The swirl (no fade, no emitters) for 60 steps on the GPU: no pigment channel's range ever grows
// (the lower bound is min(previous minimum, 0): advection writes magnitudes below 1e-30 as 0).
TEST_P(GpuAdvectionStepsTest, KeepsTheMaximumPrinciple) {
    auto scenario = fluid::makeScenario("swirl", {32, 32, 4});
    ASSERT_TRUE(scenario.ok()) << scenario.error().message;
    const fluid::Scenario& s = scenario.value();
    SolverOptions options = s.options;
    options.advection = GetParam();
    auto created = fluid::SmokeSolver::create(ctx(), options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    fluid::SmokeSolver& gpu = *created.value();
    gpu.setState(s.initial);
    auto range = [](const std::vector<float>& pigment, int channel) {
        float lo = pigment[size_t(channel)], hi = lo;
        for (size_t i = size_t(channel); i < pigment.size(); i += 4) {
            lo = std::min(lo, pigment[i]);
            hi = std::max(hi, pigment[i]);
        }
        return std::pair<float, float>(lo, hi);
    };
    FieldState previous = s.initial;
    for (uint32_t step = 0; step < 60; ++step) {
        ASSERT_TRUE(gpu.setEmitters(s.emitters(step)).ok());
        gpu.step();
        const FieldState now = gpu.state();
        for (int c = 0; c < 4; ++c) {
            const auto [lo, hi] = range(now.pigment, c);
            const auto [previousLo, previousHi] = range(previous.pigment, c);
            ASSERT_GE(lo, std::min(previousLo, 0.0f)) << "step " << step << " channel " << c;
            ASSERT_LE(hi, previousHi) << "step " << step << " channel " << c;
        }
        previous = now;
    }
    EXPECT_GT(fluid::difference(previous, s.initial).pigment.maxAbs, 0.1)
        << "the swirl must have moved the pigment";
}

INSTANTIATE_TEST_SUITE_P(GpuAdvection, GpuAdvectionStepsTest,
                         ::testing::Values(AdvectionScheme::MacCormack, AdvectionScheme::Bfecc),
                         [](const auto& param) {
                             std::string name = fluid::advectionName(param.param);
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

} // namespace
} // namespace mfx::test
