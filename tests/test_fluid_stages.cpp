// Every solver stage alone, GPU against the CPU reference, from the same input, fp32:
// relative L2 difference at most 1e-5 for every field.
#include "fluid/field_compare.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/smoke_solver.h"
#include "tests/fluid_side_by_side.h"
#include "tests/fluid_test_util.h"
#include "tests/gpu_test.h"

namespace mfx::test {
namespace {

struct StageCase {
    fluid::Stage stage;
    bool mixedBoundaries;
};

std::string caseName(const ::testing::TestParamInfo<StageCase>& info) {
    return std::string(fluid::stageName(info.param.stage)) +
           (info.param.mixedBoundaries ? "_mixed" : "_closed");
}

class FluidStageTest : public GpuTest, public ::testing::WithParamInterface<StageCase> {};

TEST_P(FluidStageTest, GpuMatchesReference) {
    const StageCase c = GetParam();
    const fluid::SolverOptions options =
        c.mixedBoundaries ? mixedBoundaryOptions() : closedBoxOptions();
    const fluid::FieldState input = randomState(options.grid, 1234);
    const auto emitters = twoEmitters(options.grid);

    const StageSideBySide run = runStageSideBySide(ctx(), options, input, c.stage, emitters);
    if (!run.ok) return;
    const fluid::FieldState& gpuState = run.gpu;
    const fluid::FieldState& cpuState = run.cpu;
    const fluid::StateDifference d = fluid::difference(gpuState, cpuState);
    expectClose(d, 1e-5, fluid::stageName(c.stage));
    // The stage must have done something comparable: the input itself differs from the output
    // for the stages that change it (guards against comparing two untouched copies).
    if (c.stage != fluid::Stage::ApplyBoundaries) {
        const fluid::StateDifference moved = fluid::difference(cpuState, input);
        EXPECT_GT(moved.maxRelL2(), 1e-3) << "the stage left every field as it was";
    }
}

// markSolids does nothing without solids: it is compared with solids in the grid, as every other
// stage is again, in tests/test_fluid_gpu_solids.cpp.
std::vector<StageCase> allStageCases() {
    std::vector<StageCase> cases;
    for (fluid::Stage stage : fluid::allStages())
        for (bool mixed : {false, true})
            if (stage != fluid::Stage::MarkSolids) cases.push_back({stage, mixed});
    return cases;
}

INSTANTIATE_TEST_SUITE_P(Stages, FluidStageTest, ::testing::ValuesIn(allStageCases()), caseName);

// applyBoundaries runs alone only, not in a step (fluid/stage_table.h): the stages keep the faces
// as the boundaries want them (advectVelocity zeroes wall-normal faces and computes a periodic
// axis's last face as its first; the later stages and the projection keep the two equal). So after
// a whole step from random fields, which break both rules, the boundaries change nothing, bit for
// bit, on the reference (fp64) and on the GPU, for every boundary set.
class StepBoundariesTest : public GpuTest, public ::testing::WithParamInterface<Boundaries> {};

TEST_P(StepBoundariesTest, AStepLeavesTheFacesAsTheBoundariesWantThem) {
    fluid::SolverOptions options =
        pressureOptions({10, 9, 8, 0.1f}, GetParam(), fluid::PressureSolver::Jacobi);
    const fluid::FieldState input = randomState(options.grid, 31);
    const auto emitters = twoEmitters(options.grid);
    fluid::ReferenceSolver cpu(options);
    cpu.setState(input);
    cpu.step(emitters);
    const fluid::FieldState stepped = cpu.state();
    cpu.runStage(fluid::Stage::ApplyBoundaries, {});
    EXPECT_EQ(cpu.state().velocityX, stepped.velocityX);
    EXPECT_EQ(cpu.state().velocityY, stepped.velocityY);
    EXPECT_EQ(cpu.state().velocityZ, stepped.velocityZ);
    // Where the boundaries act (walls, periodic faces; open faces they leave alone) the random
    // input breaks their rules: they change it, so the comparison above could fail.
    if (GetParam() != Boundaries::Open) {
        fluid::ReferenceSolver raw(options);
        raw.setState(input);
        raw.runStage(fluid::Stage::ApplyBoundaries, {});
        const fluid::FieldState fixed = raw.state();
        EXPECT_TRUE(fixed.velocityX != input.velocityX || fixed.velocityY != input.velocityY ||
                    fixed.velocityZ != input.velocityZ);
    }

    auto gpu = fluid::SmokeSolver::create(ctx(), options).value();
    gpu->setState(input);
    ASSERT_TRUE(gpu->setEmitters(emitters));
    gpu->step();
    const fluid::FieldState gpuStepped = gpu->state();
    gpu->runStage(fluid::Stage::ApplyBoundaries);
    EXPECT_EQ(gpu->state().velocityX, gpuStepped.velocityX);
    EXPECT_EQ(gpu->state().velocityY, gpuStepped.velocityY);
    EXPECT_EQ(gpu->state().velocityZ, gpuStepped.velocityZ);
}

INSTANTIATE_TEST_SUITE_P(Fluid, StepBoundariesTest, ::testing::ValuesIn(kAllBoundaries),
                         [](const ::testing::TestParamInfo<Boundaries>& param) {
                             return std::string(boundariesName(param.param));
                         });

using FluidPressureTest = GpuTest;

// Ping-pong parity: odd and even sweep counts must both leave the result in the live image.
TEST_F(FluidPressureTest, OddAndEvenJacobiCountsMatchReference) {
    for (uint32_t sweeps : {0u, 1u, 2u, 7u, 8u}) {
        fluid::SolverOptions options = mixedBoundaryOptions();
        options.jacobiIterations = sweeps;
        options.warmStart = true;
        const fluid::FieldState input = randomState(options.grid, 99 + sweeps);
        auto created = fluid::SmokeSolver::create(ctx(), options);
        ASSERT_TRUE(created.ok());
        fluid::SmokeSolver& gpu = *created.value();
        gpu.setState(input);
        gpu.runStage(fluid::Stage::SolvePressure);
        gpu.runStage(fluid::Stage::Project);
        fluid::ReferenceSolver cpu(options);
        cpu.setState(input);
        cpu.solvePressure();
        cpu.project();
        expectClose(fluid::difference(gpu.state(), cpu.state()), 1e-5,
                    std::to_string(sweeps) + " sweeps");
    }
}

// The pressure kernel works on bricks of several cells: grids that are not multiples of a brick
// (13 = 3 x 4 + 1 along x, 9 layers along z, a one-cell axis) with every boundary kind on every
// axis, so that cells next to each face, inside, and in partial bricks are all checked.
TEST_F(FluidPressureTest, OddGridsWithEveryBoundaryKindMatchReference) {
    using fluid::Boundary;
    struct AxisKinds {
        Boundary low, high;
    };
    const AxisKinds walls{Boundary::WallFreeSlip, Boundary::WallNoSlip};
    const AxisKinds open{Boundary::Open, Boundary::Open};
    const AxisKinds periodic{Boundary::Periodic, Boundary::Periodic};
    const AxisKinds openWall{Boundary::Open, Boundary::WallFreeSlip};
    const std::array<AxisKinds, 3> layouts[] = {{walls, walls, walls},
                                                {open, open, open},
                                                {periodic, periodic, periodic},
                                                {periodic, openWall, walls},
                                                {openWall, periodic, open}};
    const fluid::GridShape grids[] = {{13, 7, 9, 0.1f}, {5, 1, 6, 0.2f}, {1, 3, 2, 0.25f}};
    uint32_t seed = 500;
    for (const fluid::GridShape& grid : grids)
        for (const auto& layout : layouts)
            for (uint32_t sweeps : {1u, 2u, 5u}) {
                fluid::SolverOptions options = closedBoxOptions(grid);
                for (int axis = 0; axis < 3; ++axis) {
                    options.boundaries[2 * axis].kind = layout[axis].low;
                    options.boundaries[2 * axis + 1].kind = layout[axis].high;
                }
                options.jacobiIterations = sweeps;
                options.warmStart = true;
                const fluid::FieldState input = randomState(grid, ++seed);
                const StageSideBySide run =
                    runStageSideBySide(ctx(), options, input, fluid::Stage::SolvePressure);
                ASSERT_TRUE(run.ok);
                const fluid::StateDifference d = fluid::difference(run.gpu, run.cpu);
                EXPECT_LE(d.pressure.relL2, 1e-5)
                    << grid.cellsX << "x" << grid.cellsY << "x" << grid.cellsZ << ", layout "
                    << (&layout - layouts) << ", " << sweeps << " sweeps (max abs "
                    << d.pressure.maxAbs << ")";
            }
}

} // namespace
} // namespace mfx::test
