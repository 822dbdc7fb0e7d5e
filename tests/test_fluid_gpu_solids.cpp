// Moving solids in the GPU smoke solver (docs/fluid.md, "Solids"; shaders/fluid/mark_solids.comp
// and fluid_solids.glsl) against the CPU reference's (tests/test_fluid_solids.cpp): every stage
// alone with a moving sphere and capsule in the grid, fp32 and fp16, each advection scheme; 100
// steps with a capsule swept through a puff; a still sphere in a stream that lets nothing through;
// a moving sphere that pushes the air and leaves a wake; both store paths the same bits; no solids
// the solver as before; bad solids and solvers that do not take them refused in one line.
#include "core/anim/fighter.h"
#include "core/anim/sampling.h"
#include "fluid/body_solids.h"
#include "fluid/field_compare.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/scenarios.h"
#include "fluid/smoke_solver.h"
#include "tests/fluid_side_by_side.h"
#include "tests/fluid_solids_util.h"
#include "tests/gpu_test.h"
#include "tests/kick_band_util.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <vector>

namespace mfx::test {
namespace {

using fluid::AdvectionScheme;
using fluid::FieldState;
using fluid::ReferenceSolver;
using fluid::SmokeSolver;
using fluid::SolverOptions;
using fluid::Stage;
using fluid::Storage;

shared::FluidSolid capsule(glm::vec3 a, glm::vec3 b, float radius, glm::vec3 velocityA,
                           glm::vec3 velocityB) {
    return solidCapsule(a, b, radius, velocityA, velocityB);
}

shared::FluidSolid sphere(glm::vec3 centre, float radius, glm::vec3 velocity = glm::vec3(0.0f)) {
    return solidSphere(centre, radius, velocity);
}

struct SolidStageCase {
    Stage stage;
    bool mixedBoundaries;
    Storage storage;
    AdvectionScheme scheme;
    fluid::PressureSolver pressure = fluid::PressureSolver::Jacobi;
    // MultigridOptions::coarseCells (0: the default, which fuses these small grids' whole V-cycle
    // into cycle_coarse_levels; 64: level 0 dispatched on its own).
    uint32_t coarseCells = 0;
};

std::string caseName(const ::testing::TestParamInfo<SolidStageCase>& info) {
    const SolidStageCase& c = info.param;
    std::string name =
        std::string(fluid::stageName(c.stage)) + (c.mixedBoundaries ? "_mixed" : "_closed");
    if (c.storage == Storage::Float16) name += "_fp16";
    if (c.scheme != AdvectionScheme::SemiLagrangian)
        name += std::string("_") + fluid::advectionName(c.scheme);
    if (c.pressure != fluid::PressureSolver::Jacobi)
        name += std::string("_") + fluid::pressureSolverName(c.pressure);
    if (c.coarseCells != 0) name += "_unfused";
    return name;
}

class GpuSolidsStageTest : public GpuTest, public ::testing::WithParamInterface<SolidStageCase> {};

// From random fields with the solids marked, each stage on the GPU against the reference: 1e-5
// relative L2 in fp32 (the stages' bound, tests/test_fluid_stages.cpp), one binary16 step in fp16
// (tests/test_fluid_gpu_half.cpp). The solids must matter to the stage on this input: the
// reference without them gives another result.
TEST_P(GpuSolidsStageTest, GpuMatchesReference) {
    const SolidStageCase c = GetParam();
    SolverOptions options = c.mixedBoundaries ? mixedBoundaryOptions() : closedBoxOptions();
    options.storage = c.storage;
    options.advection = c.scheme;
    options.pressureSolver = c.pressure;
    options.multigrid.coarseCells = c.coarseCells;
    const FieldState input = randomState(options.grid, 2718);
    const auto emitters = twoEmitters(options.grid);
    const auto solids = twoSolids(options.grid);
    ASSERT_GT(surfaceMargin(options.grid, solids), 1e-5);

    ReferenceSolver cpu(options);
    cpu.setState(input);
    cpu.setSolids(solids);
    // Marked as the GPU marks them: the stage (setSolids marks too, but stores no fp16 rounding).
    cpu.runStage(Stage::MarkSolids, {});
    const FieldState marked = cpu.state();
    cpu.runStage(c.stage, emitters);

    auto created = SmokeSolver::create(ctx(), options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    SmokeSolver& gpu = *created.value();
    gpu.setState(input);
    ASSERT_TRUE(gpu.setEmitters(emitters).ok());
    ASSERT_TRUE(gpu.setSolids(solids).ok());
    ASSERT_TRUE(gpu.hasSolids());
    gpu.runStage(Stage::MarkSolids);
    if (c.stage != Stage::MarkSolids) gpu.runStage(c.stage);

    const fluid::StateDifference d = fluid::difference(gpu.state(), cpu.state());
    printDifference(fluid::stageName(c.stage), d);
    const double bound = c.storage == Storage::Float16 ? 1.0 / 2048.0 : 1e-5;
    EXPECT_LE(d.velocity.relL2, bound) << "velocity (max abs " << d.velocity.maxAbs << ")";
    EXPECT_LE(d.pressure.relL2, bound) << "pressure (max abs " << d.pressure.maxAbs << ")";
    EXPECT_LE(d.pigment.relL2, bound) << "pigment (max abs " << d.pigment.maxAbs << ")";
    EXPECT_LE(d.divergence.relL2, 1e-5) << "divergence (max abs " << d.divergence.maxAbs << ")";

    // Without the solids the same stage from the same marked fields ends elsewhere.
    FieldState without;
    if (c.stage == Stage::MarkSolids) {
        without = input;
    } else {
        ReferenceSolver plain(options);
        plain.setState(marked);
        plain.runStage(c.stage, emitters);
        without = plain.state();
    }
    EXPECT_GT(fluid::difference(cpu.state(), without).maxRelL2(), 1e-3)
        << "the solids changed nothing in this stage";
}

std::vector<SolidStageCase> solidStageCases() {
    std::vector<SolidStageCase> cases;
    for (Stage stage : fluid::stepOrder())
        for (bool mixed : {false, true})
            cases.push_back({stage, mixed, Storage::Float32, AdvectionScheme::SemiLagrangian});
    for (Stage stage : fluid::stepOrder())
        cases.push_back({stage, true, Storage::Float16, AdvectionScheme::SemiLagrangian});
    for (AdvectionScheme scheme : {AdvectionScheme::MacCormack, AdvectionScheme::Bfecc})
        for (Stage stage : {Stage::AdvectVelocity, Stage::AdvectPigment})
            cases.push_back({stage, true, Storage::Float32, scheme});
    // The other pressure solvers (their level 0 reads the solids' flags), each V-cycle fused
    // into one workgroup and with level 0 dispatched on its own.
    for (fluid::PressureSolver solver :
         {fluid::PressureSolver::RedBlackGaussSeidel, fluid::PressureSolver::Multigrid,
          fluid::PressureSolver::MultigridPcg})
        for (bool mixed : {false, true})
            for (uint32_t coarseCells : {0u, 64u}) {
                if (solver == fluid::PressureSolver::RedBlackGaussSeidel && coarseCells != 0)
                    continue; // no hierarchy
                cases.push_back({Stage::SolvePressure, mixed, Storage::Float32,
                                 AdvectionScheme::SemiLagrangian, solver, coarseCells});
            }
    return cases;
}

INSTANTIATE_TEST_SUITE_P(GpuSolids, GpuSolidsStageTest, ::testing::ValuesIn(solidStageCases()),
                         caseName);

// The puff for `steps` steps at 16³ with a capsule swept through it (its ends moving on two
// different lines, so it turns), GPU and reference side by side.
void sweptCapsuleSideBySide(const gpu::Context& ctx, uint32_t steps,
                            const std::function<void(SolverOptions&)>& adjust, SideBySide& out) {
    auto scenario = fluid::makeScenario("puff", {16, 16, 16});
    ASSERT_TRUE(scenario.ok()) << scenario.error().message;
    const fluid::Scenario& s = scenario.value();
    out.options = s.options;
    if (adjust) adjust(out.options);
    const fluid::GridShape& g = out.options.grid;
    const glm::vec3 size = glm::vec3(g.cellsX, g.cellsY, g.cellsZ) * g.cellSize;
    auto created = SmokeSolver::create(ctx, out.options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    SmokeSolver& gpu = *created.value();
    ReferenceSolver cpu(out.options);
    gpu.setState(s.initial);
    cpu.setState(s.initial);
    const float dt = out.options.dt;
    for (uint32_t step = 0; step < steps; ++step) {
        // End A crosses the box along x, end B along z and up; where the step ends.
        const float t = float(step + 1) * dt;
        const glm::vec3 velocityA = size * glm::vec3(0.35f, 0.0f, 0.0f);
        const glm::vec3 velocityB = size * glm::vec3(0.0f, 0.1f, 0.3f);
        const glm::vec3 a = size * glm::vec3(0.13f, 0.36f, 0.52f) + velocityA * t;
        const glm::vec3 b = size * glm::vec3(0.47f, 0.57f, 0.19f) + velocityB * t;
        const shared::FluidSolid solid = capsule(a, b, 0.11f * size.x, velocityA, velocityB);
        const auto emitters = s.emitters(step);
        ASSERT_TRUE(gpu.setEmitters(emitters).ok());
        ASSERT_TRUE(gpu.setSolids(std::span(&solid, 1)).ok());
        cpu.setSolids(std::span(&solid, 1));
        gpu.step();
        cpu.step(emitters);
    }
    out.gpu = gpu.state();
    out.cpu = cpu.state();
    out.difference = fluid::difference(out.gpu, out.cpu);
}

using GpuSolidsTest = GpuTest;

// 100 steps with a moving solid: within the bound of the 100-step comparisons without solids
// (tests/test_fluid_steps.cpp, 1e-4). A cell whose centre the fp32 and fp64 capsule put on
// different sides of its surface in some step would differ by the cell's whole pigment and
// velocity: the sweep's geometry keeps every centre clear of the surface at every step.
TEST_F(GpuSolidsTest, HundredStepsWithASweptCapsuleStayCloseToReference) {
    SideBySide run;
    sweptCapsuleSideBySide(ctx(), 100, nullptr, run);
    if (HasFatalFailure()) return;
    printDifference("100 steps, swept capsule", run.difference);
    expectClose(run.difference, 1e-4, "100 steps with a swept capsule");
    expectMovingAndFinite(run);
}

// The other pressure solvers with a moving solid, 40 steps each: within the same bound.
TEST_F(GpuSolidsTest, EveryPressureSolverFollowsTheReferenceWithASweptCapsule) {
    for (fluid::PressureSolver solver :
         {fluid::PressureSolver::RedBlackGaussSeidel, fluid::PressureSolver::Multigrid,
          fluid::PressureSolver::MultigridPcg}) {
        SideBySide run;
        sweptCapsuleSideBySide(
            ctx(), 40, [&](SolverOptions& o) { o.pressureSolver = solver; }, run);
        if (HasFatalFailure()) return;
        const std::string name =
            std::string("40 steps, swept capsule, ") + fluid::pressureSolverName(solver);
        printDifference(name, run.difference);
        expectClose(run.difference, 1e-4, name);
        expectMovingAndFinite(run);
    }
}

// Buffer and direct stores: the same bits with solids, over 10 steps.
TEST_F(GpuSolidsTest, BothStorePathsStoreTheSameBitsWithSolids) {
    SideBySide buffer, direct;
    sweptCapsuleSideBySide(
        ctx(), 10, [](SolverOptions& o) { o.storePath = fluid::StorePath::Buffer; }, buffer);
    if (HasFatalFailure()) return;
    sweptCapsuleSideBySide(
        ctx(), 10, [](SolverOptions& o) { o.storePath = fluid::StorePath::Direct; }, direct);
    if (HasFatalFailure()) return;
    expectSameBits(buffer.gpu, direct.gpu);
}

// The stages split into the workgroup blocks away from the solids and those near them
// (SolverOptions::solidLists, fluid_solids.glsl's block lists) compute what the whole dispatches
// compute, bit for bit: in a closed box, and with mixed boundaries (a periodic axis), viscosity
// and MacCormack advection, so that every stage that reads solids runs split, its passes too.
TEST_F(GpuSolidsTest, SplitStagesStoreTheSameBitsAsWholeOnes) {
    for (bool mixed : {false, true}) {
        SCOPED_TRACE(mixed ? "mixed boundaries" : "closed box");
        auto adjust = [mixed](fluid::ByDevice lists) {
            return [mixed, lists](SolverOptions& o) {
                o.solidLists = lists;
                o.workgroup = {4, 4, 4}; // 125 blocks over the 16³ cells + 1
                if (!mixed) return;
                o.boundaries = mixedBoundaryOptions(o.grid).boundaries;
                o.viscosity = 0.02f;
                o.viscosityIterations = 3;
                o.advection = AdvectionScheme::MacCormack;
            };
        };
        SideBySide split, whole;
        sweptCapsuleSideBySide(ctx(), 5, adjust(fluid::ByDevice::On), split);
        if (HasFatalFailure()) return;
        sweptCapsuleSideBySide(ctx(), 5, adjust(fluid::ByDevice::Off), whole);
        if (HasFatalFailure()) return;
        expectSameBits(split.gpu, whole.gpu);
        // And in the closed box both are the solver the 100-step comparison checks (its bound;
        // the mixed case's stages are checked one by one above).
        if (!mixed) {
            EXPECT_LE(split.difference.velocity.relL2, 1e-4);
            EXPECT_LE(split.difference.pigment.relL2, 1e-4);
        }
    }
}

// Auto splits on a CPU device only; On and Off as asked; never without solids.
TEST_F(GpuSolidsTest, TheStagesAreSplitWhereAskedAndOnlyWithSolids) {
    const shared::FluidSolid ball = sphere({0.5f, 0.5f, 0.5f}, 0.2f);
    for (fluid::ByDevice lists :
         {fluid::ByDevice::Auto, fluid::ByDevice::On, fluid::ByDevice::Off}) {
        SolverOptions options = closedBoxOptions();
        options.solidLists = lists;
        auto created = SmokeSolver::create(ctx(), options);
        ASSERT_TRUE(created.ok()) << created.error().message;
        SmokeSolver& solver = *created.value();
        EXPECT_FALSE(solver.splitsSolidStages());
        ASSERT_TRUE(solver.setSolids(std::span(&ball, 1)).ok());
        const bool expected = lists == fluid::ByDevice::On ||
                              (lists == fluid::ByDevice::Auto && ctx().info().isCpu());
        EXPECT_EQ(solver.splitsSolidStages(), expected);
        EXPECT_EQ(fluid::splitsSolids(lists, ctx()), expected);
        // Split, a step records each split stage's two halves: more dispatches than whole.
        solver.step();
        uint32_t dispatches = 0;
        for (const auto& [stage, count] : solver.lastStepDispatches())
            dispatches += count;
        ASSERT_TRUE(solver.setSolids({}).ok());
        EXPECT_FALSE(solver.splitsSolidStages());
        solver.step();
        uint32_t without = 0;
        for (const auto& [stage, count] : solver.lastStepDispatches())
            without += count;
        if (expected) {
            EXPECT_GT(dispatches, without + 8);
        }
    }
}

// The root mean square divergence of `state`'s velocity over the cells `marks` calls fluid.
double fluidDivergence(const ReferenceSolver& marks, const FieldState& state) {
    const fluid::GridShape& g = state.grid;
    double squares = 0.0;
    int cells = 0;
    for (int k = 0; k < int(g.cellsZ); ++k)
        for (int j = 0; j < int(g.cellsY); ++j)
            for (int i = 0; i < int(g.cellsX); ++i) {
                if (marks.solidCell({i, j, k})) continue;
                double div = 0.0;
                for (int c = 0; c < 3; ++c) {
                    glm::ivec3 hi(i, j, k);
                    hi[c] += 1;
                    div += double(component(state, c)[marks.faceIndex(c, hi)]) -
                           double(component(state, c)[marks.faceIndex(c, {i, j, k})]);
                }
                div /= double(g.cellSize);
                squares += div * div;
                ++cells;
            }
    return std::sqrt(squares / std::max(cells, 1));
}

TEST_F(GpuSolidsTest, AStillSphereInAUniformStreamLetsNothingThroughItsFaces) {
    SolverOptions options = streamOptions();
    options.jacobiIterations = 400; // near convergence, so the two divergences compare the solids
    FieldState stream = FieldState::zero(kStreamGrid);
    for (float& u : stream.velocityX)
        u = 1.0f;
    const shared::FluidSolid ball = sphere({1.0f, 0.5f, 0.5f}, 0.2f);
    ReferenceSolver marks(options);
    marks.setSolids(std::span(&ball, 1));
    // A pulse of random air on the stream, so that the step has divergence to remove.
    FieldState start = stream;
    const FieldState noise = randomState(kStreamGrid, 5);
    for (int c = 0; c < 3; ++c)
        for (size_t i = 0; i < component(start, c).size(); ++i)
            component(start, c)[i] += 0.5f * component(noise, c)[i];
    double divergence[2] = {0.0, 0.0};
    for (int with = 0; with < 2; ++with) {
        auto gpu = SmokeSolver::create(ctx(), options).value();
        gpu->setState(start);
        if (with) {
            ASSERT_TRUE(gpu->setSolids(std::span(&ball, 1)).ok());
        }
        gpu->step();
        const FieldState state = gpu->state();
        divergence[with] = fluidDivergence(marks, state);
        if (with) {
            EXPECT_EQ(solidFaceError(marks, state, glm::dvec3(0.0)), 0.0)
                << "flux through the sphere's faces";
        }
    }
    const double before = fluidDivergence(marks, start);
    std::printf("rms divergence over the fluid cells: %.3g before the step; after it %.3g with "
                "the sphere, %.3g without\n",
                before, divergence[1], divergence[0]);
    EXPECT_LT(divergence[1], 0.05 * before);
    EXPECT_LE(divergence[1], 1.5 * divergence[0]) << "the sphere leaves more divergence";
}

TEST_F(GpuSolidsTest, AMovingSphereCarriesItsFacesPushesTheAirAsideAndLeavesAWake) {
    SolverOptions options = streamOptions();
    options.jacobiIterations = 80;
    options.integrator = fluid::Integrator::RK2;
    auto gpu = SmokeSolver::create(ctx(), options).value();
    gpu->setState(FieldState::zero(kStreamGrid));
    const glm::vec3 velocity(2.0f, 0.0f, 0.0f);
    const double radius = 0.15;
    glm::vec3 centre(0.4f, 0.5f, 0.5f);
    ReferenceSolver marks(options);
    for (int step = 0; step < 24; ++step) {
        centre += velocity * options.dt;
        const shared::FluidSolid ball = sphere(centre, float(radius), velocity);
        ASSERT_TRUE(gpu->setSolids(std::span(&ball, 1)).ok());
        marks.setSolids(std::span(&ball, 1));
        gpu->step();
        ASSERT_EQ(solidFaceError(marks, gpu->state(), glm::dvec3(velocity)), 0.0)
            << "step " << step;
    }
    const FieldState state = gpu->state();
    const double h = kStreamGrid.cellSize;
    const glm::dvec3 at(centre);
    const FlowRegion ahead =
        flowRegion(state, marks, at, at.x + radius, at.x + radius + 4 * h, radius);
    const FlowRegion behind =
        flowRegion(state, marks, at, at.x - radius - 6 * h, at.x - radius, radius);
    std::printf("GPU: ahead of the sphere mean u_x %.3f m/s, mean |curl| %.2f /s; behind %.3f, "
                "%.2f\n",
                ahead.meanU, ahead.meanCurl, behind.meanU, behind.meanCurl);
    EXPECT_GT(ahead.meanU, 0.2 * double(velocity.x)) << "the air ahead is pushed";
    EXPECT_GT(behind.meanCurl, ahead.meanCurl) << "a wake behind";
}

// Solids set and then removed before a step: the step is the solver without solids, bit for bit
// (the stages compile without the solid tests again).
TEST_F(GpuSolidsTest, RemovedSolidsLeaveTheSolverAsItWas) {
    const SolverOptions options = mixedBoundaryOptions();
    const FieldState input = randomState(options.grid, 77);
    const auto emitters = twoEmitters(options.grid);
    const auto solids = twoSolids(options.grid);
    FieldState states[2];
    for (int i = 0; i < 2; ++i) {
        auto gpu = SmokeSolver::create(ctx(), options).value();
        gpu->setState(input);
        ASSERT_TRUE(gpu->setEmitters(emitters).ok());
        if (i == 1) {
            ASSERT_TRUE(gpu->setSolids(solids).ok());
            ASSERT_TRUE(gpu->setSolids({}).ok());
            EXPECT_FALSE(gpu->hasSolids());
        }
        gpu->step();
        states[i] = gpu->state();
    }
    EXPECT_EQ(fluid::difference(states[0], states[1]).maxRelL2(), 0.0);
    EXPECT_EQ(states[0].pigment, states[1].pigment);
    EXPECT_EQ(states[0].velocityY, states[1].velocityY);
}

TEST_F(GpuSolidsTest, BadSolidsAndSolversWithoutSolidsAreRefusedInOneLine) {
    auto gpu = SmokeSolver::create(ctx(), closedBoxOptions()).value();
    shared::FluidSolid bad = sphere({0.5f, 0.5f, 0.5f}, 0.2f);
    bad.velocityB.y = std::numeric_limits<float>::quiet_NaN();
    const Status nan = gpu->setSolids(std::span(&bad, 1));
    ASSERT_FALSE(nan.ok());
    EXPECT_EQ(nan.error().message, "solid 0: a velocity is not finite");
    EXPECT_FALSE(gpu->hasSolids());

    // A multigrid of one level (its coarse levels do not see the solids: one is needed).
    SolverOptions multigrid = closedBoxOptions({6, 5, 4, 0.125f}); // solved exactly on the GPU
    multigrid.pressureSolver = fluid::PressureSolver::Multigrid;
    multigrid.multigrid.levels = 1;
    auto other = SmokeSolver::create(ctx(), multigrid).value();
    const shared::FluidSolid ball = sphere({0.4f, 0.3f, 0.25f}, 0.2f);
    const Status refused = other->setSolids(std::span(&ball, 1));
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().message,
              "solids: the pressure solver \"multigrid\" takes solids only with two multigrid "
              "levels or more");
    EXPECT_EQ(refused.error().message.find('\n'), std::string::npos);
}

// The fighter's roundhouse kick (its body capsules, fluid/body_solids.h) through a band of smoke,
// as the reference's test (test_fluid_solids.cpp) on the GPU: at most 1% of the pigment in the
// body's solid cells after every step (none, by the solid rules), and the band's air set moving.
TEST_F(GpuSolidsTest, TheKickThroughACloudPushesItAndNeverHoldsPigmentInside) {
    const SolverOptions options = kickBandOptions();
    auto with = SmokeSolver::create(ctx(), options).value();
    auto without = SmokeSolver::create(ctx(), options).value();
    with->setState(kickBandCloud(options.grid));
    without->setState(kickBandCloud(options.grid));
    const KickBandRun run = runKickThroughBand(
        options,
        [&](const std::vector<shared::FluidSolid>& solids) {
            ASSERT_TRUE(with->setSolids(solids).ok());
            with->step();
            without->step();
        },
        [&] { return with->state(); }, [&] { return without->state(); });
    std::printf(
        "GPU kick through a band of smoke: at most %.2g of the pigment inside the body; the "
        "band's air at %.3f m/s (%.3f without the body)\n",
        run.largestInside, run.speed, run.stillSpeed);
    EXPECT_LE(run.largestInside, 0.01);
    EXPECT_GT(run.speed, 0.05);
    EXPECT_LT(run.stillSpeed, 1e-6);
}

} // namespace
} // namespace mfx::test
