// Whole steps: every scenario run for 100 steps on the GPU and on the CPU reference from the same
// input stays within a documented tolerance.
#include "fluid/field_compare.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/scenarios.h"
#include "fluid/smoke_solver.h"
#include "tests/fluid_side_by_side.h"
#include "tests/gpu_test.h"

namespace mfx::test {
namespace {

class FluidStepsTest : public GpuTest, public ::testing::WithParamInterface<const char*> {};

// fp32 (GPU) against fp64 (CPU): each stage agrees to ~1e-6 (test_fluid_stages.cpp); over 100
// steps of 11 stages the rounding differences accumulate but are not amplified much (measured
// with `motionfx compare SCENARIO --steps 100 --grid 16x16x16` on lavapipe: at most 2.4e-5, in
// the divergence field, which is a difference of nearly equal face values). 1e-4 leaves room for
// other CPUs' rounding, and is still 10x below what a wrong stage (~1e-1) produces.
constexpr double kHundredStepTolerance = 1e-4;

TEST_P(FluidStepsTest, HundredStepsStayCloseToReference) {
    SideBySide run;
    runSideBySide(ctx(), GetParam(), {16, 16, 16}, 100, nullptr, run);
    if (HasFatalFailure()) return;
    const fluid::FieldState& cpuState = run.cpu;
    const fluid::StateDifference& d = run.difference;
    EXPECT_LE(d.velocity.relL2, kHundredStepTolerance);
    EXPECT_LE(d.pressure.relL2, kHundredStepTolerance);
    EXPECT_LE(d.pigment.relL2, kHundredStepTolerance);
    EXPECT_LE(d.divergence.relL2, kHundredStepTolerance);
    // Something happened: the flow is not at rest and there is pigment.
    const fluid::Diagnostics diagnostics = fluid::computeDiagnostics(run.options, cpuState);
    EXPECT_GT(diagnostics.kineticEnergy, 1e-6);
    EXPECT_GT(diagnostics.totalPigment.w, 1e-6);
    EXPECT_EQ(diagnostics.nonFinite, 0u);
}

// The workgroup shape is a performance setting only: an odd shape that leaves partial groups on
// every axis gives bit-for-bit the same fields as the default.
TEST_F(GpuTest, FluidWorkgroupShapeDoesNotChangeResults) {
    auto scenario = fluid::makeScenario("puff", {13, 16, 11});
    ASSERT_TRUE(scenario.ok()) << scenario.error().message;
    fluid::FieldState states[2];
    const std::array<uint32_t, 3> shapes[2] = {fluid::SolverOptions{}.workgroup, {5, 3, 2}};
    for (int i = 0; i < 2; ++i) {
        fluid::SolverOptions options = scenario.value().options;
        options.workgroup = shapes[i];
        auto created = fluid::SmokeSolver::create(ctx(), options);
        ASSERT_TRUE(created.ok()) << created.error().message;
        fluid::SmokeSolver& gpu = *created.value();
        gpu.setState(scenario.value().initial);
        for (uint32_t step = 0; step < 12; ++step) {
            ASSERT_TRUE(gpu.setEmitters(scenario.value().emitters(step)).ok());
            gpu.step();
        }
        states[i] = gpu.state();
    }
    EXPECT_EQ(states[0].velocityX, states[1].velocityX);
    EXPECT_EQ(states[0].velocityY, states[1].velocityY);
    EXPECT_EQ(states[0].velocityZ, states[1].velocityZ);
    EXPECT_EQ(states[0].pressure, states[1].pressure);
    EXPECT_EQ(states[0].pigment, states[1].pigment);
    EXPECT_GT(fluid::computeDiagnostics(scenario.value().options, states[0]).totalPigment.w, 0.0);
}

TEST_F(GpuTest, FluidBadWorkgroupIsRefused) {
    fluid::SolverOptions options;
    options.grid = {8, 8, 8, 0.125f};
    for (const std::array<uint32_t, 3>& shape :
         {std::array<uint32_t, 3>{0, 8, 4}, std::array<uint32_t, 3>{64, 64, 64}}) {
        options.workgroup = shape;
        auto created = fluid::SmokeSolver::create(ctx(), options);
        ASSERT_FALSE(created.ok());
        EXPECT_NE(created.error().message.find("workgroup"), std::string::npos)
            << created.error().message;
    }
}

INSTANTIATE_TEST_SUITE_P(Scenarios, FluidStepsTest,
                         ::testing::Values("puff", "jet", "swirl", "random-impulses"),
                         [](const auto& param) {
                             std::string name = param.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

} // namespace
} // namespace mfx::test
