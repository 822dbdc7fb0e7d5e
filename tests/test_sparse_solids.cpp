// Moving solids on the sparse grid (docs/fluid.md, "Solids" and "Sparse domain";
// shaders/fluid/sparse_mark_solids.comp, sparse_solids.glsl): every stage alone with a moving
// sphere and capsule, on about half the bricks (solid cells in inactive bricks are air) against the
// reference with the same active cells, and on every brick against the dense GPU solver; 100 steps
// of a capsule swept through a puff; the GPU rebuild wants the bricks the solids reach, as the
// layout's twin does; a grid with solids settles on its pigment alone; the kick through a cloud.
#include "core/anim/body_capsules.h"
#include "core/anim/fighter.h"
#include "core/anim/sampling.h"
#include "core/gpu/commands.h"
#include "fluid/body_solids.h"
#include "fluid/field_compare.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/scenarios.h"
#include "fluid/smoke_solver.h"
#include "tests/fluid_side_by_side.h"
#include "tests/fluid_solids_util.h"
#include "tests/gpu_test.h"
#include "tests/kick_band_util.h"
#include "tests/sparse_test_util.h"

#include <algorithm>
#include <cstdio>
#include <vector>

namespace mfx::test {
namespace {

using fluid::FieldState;
using fluid::ReferenceSolver;
using fluid::SparseSmokeSolver;
using fluid::Stage;
using namespace sparse_test; // the sparse suites' helpers (tests/sparse_test_util.h)

class SparseSolidsStageTest : public GpuTest, public ::testing::WithParamInterface<StageCase> {};

// On about half the bricks, scattered: the solids reach inactive bricks too, whose cells are air.
// The reference with the same active cells (1e-5 relative L2, the stages' bound), and without the
// solids the same stage from the same marked fields ends elsewhere.
TEST_P(SparseSolidsStageTest, SomeBricksActiveEqualsTheReferenceOnTheSameCells) {
    const StageCase c = GetParam();
    const SolverOptions o = (c.walls ? wallOptions : openOptions)({32, 24, 24, 0.08f});
    const auto solids = twoSolids(o.grid);
    ASSERT_GT(surfaceMargin(o.grid, solids), 1e-5);
    auto sparse = makeSparse(ctx(), o);
    ASSERT_TRUE(sparse);
    activate(*sparse, scattered(c.walls ? 5 : 9));
    const std::vector<uint8_t> active = sparse->layout().activeCells();
    // Some of the solids' cells are stored and some are not.
    const std::vector<uint8_t> solidCells = fluid::solidCellMask(o.grid, solids);
    size_t storedSolid = 0, unstoredSolid = 0;
    for (size_t cell = 0; cell < solidCells.size(); ++cell)
        if (solidCells[cell]) (active[cell] ? storedSolid : unstoredSolid) += 1;
    ASSERT_GT(storedSolid, 50u);
    ASSERT_GT(unstoredSolid, 50u);

    const FieldState input = randomState(o.grid, 777);
    const auto emitters = emittersFor(o);
    sparse->setState(input);
    ASSERT_TRUE(sparse->setEmitters(emitters).ok());
    ASSERT_TRUE(sparse->setSolids(solids).ok());
    ASSERT_TRUE(sparse->hasSolids());
    sparse->runStage(Stage::MarkSolids);
    if (c.stage != Stage::MarkSolids) sparse->runStage(c.stage);
    const FieldState gpuState = sparse->state();
    EXPECT_EQ(sparse->lastSharedFaceMismatches(), 0u);

    ReferenceSolver cpu(o);
    cpu.setActiveCells(active);
    cpu.setState(input);
    const FieldState before = cpu.state();
    cpu.setSolids(solids);
    cpu.runStage(Stage::MarkSolids, {});
    const FieldState marked = cpu.state();
    cpu.runStage(c.stage, emitters);
    const fluid::StateDifference d = fluid::difference(gpuState, cpu.state());
    printDifference(fluid::stageName(c.stage), d);
    expectClose(d, 1e-5, "sparse with solids against the reference");

    FieldState without = before;
    if (c.stage != Stage::MarkSolids) {
        ReferenceSolver plain(o);
        plain.setActiveCells(active);
        plain.setState(marked);
        plain.runStage(c.stage, emitters);
        without = plain.state();
    }
    // The stored solid cells are about 1% of the domain's, and a stage like the divergence's
    // changes only those (8.5e-4 relative L2 measured): 1e-4 is still four orders above fp32's
    // differences between the two.
    EXPECT_GT(fluid::difference(cpu.state(), without).maxRelL2(), 1e-4)
        << "the solids changed nothing in this stage";
}

// On every brick: the dense GPU solver with the same solids.
TEST_P(SparseSolidsStageTest, AllBricksActiveEqualsTheDenseSolver) {
    const StageCase c = GetParam();
    const SolverOptions o = c.walls ? wallOptions() : openOptions();
    const auto solids = twoSolids(o.grid);
    ASSERT_GT(surfaceMargin(o.grid, solids), 1e-5);
    const FieldState input = randomState(o.grid, 4321);
    const auto emitters = emittersFor(o);

    auto sparse = makeSparse(ctx(), o);
    ASSERT_TRUE(sparse);
    activate(*sparse, [](glm::ivec3) { return true; });
    sparse->setState(input);
    ASSERT_TRUE(sparse->setEmitters(emitters).ok());
    ASSERT_TRUE(sparse->setSolids(solids).ok());
    sparse->runStage(Stage::MarkSolids);
    if (c.stage != Stage::MarkSolids) sparse->runStage(c.stage);
    const FieldState sparseState = sparse->state();
    EXPECT_EQ(sparse->lastSharedFaceMismatches(), 0u);

    auto dense = fluid::SmokeSolver::create(ctx(), o);
    ASSERT_TRUE(dense.ok()) << dense.error().message;
    dense.value()->setState(input);
    ASSERT_TRUE(dense.value()->setEmitters(emitters).ok());
    ASSERT_TRUE(dense.value()->setSolids(solids).ok());
    dense.value()->runStage(Stage::MarkSolids);
    if (c.stage != Stage::MarkSolids) dense.value()->runStage(c.stage);
    expectClose(fluid::difference(sparseState, dense.value()->state()), 1e-5,
                "sparse against dense GPU, with solids");
}

INSTANTIATE_TEST_SUITE_P(Stages, SparseSolidsStageTest, ::testing::ValuesIn(stageCases(true)),
                         stageCaseName);

using SparseSolidsTest = GpuTest;

// The puff at 24 x 16 x 16 with a capsule swept through it (its ends on two different lines, so it
// turns), on 10 of the 12 bricks, sparse GPU and reference side by side for 100 steps: within the
// 100-step bound (1e-4). The sweep keeps every cell centre clear of the surface at every step.
TEST_F(SparseSolidsTest, HundredStepsWithASweptCapsuleStayCloseToTheReference) {
    auto scenario = fluid::makeScenario("puff", {24, 16, 16});
    ASSERT_TRUE(scenario.ok()) << scenario.error().message;
    const fluid::Scenario& s = scenario.value();
    SolverOptions o = s.options;
    o.vorticity = 0.0f; // not on the sparse domain
    const fluid::GridShape& g = o.grid;
    const glm::vec3 size = glm::vec3(g.cellsX, g.cellsY, g.cellsZ) * g.cellSize;
    auto sparse = makeSparse(ctx(), o);
    ASSERT_TRUE(sparse);
    activate(*sparse,
             [](glm::ivec3 b) { return b != glm::ivec3(2, 1, 0) && b != glm::ivec3(0, 0, 1); });
    ReferenceSolver cpu(o);
    cpu.setActiveCells(sparse->layout().activeCells());
    sparse->setState(s.initial);
    cpu.setState(s.initial);
    for (uint32_t step = 0; step < 100; ++step) {
        const float t = float(step + 1) * o.dt;
        const glm::vec3 velocityA = size * glm::vec3(0.35f, 0.0f, 0.0f);
        const glm::vec3 velocityB = size * glm::vec3(0.0f, 0.1f, 0.3f);
        const glm::vec3 a = size * glm::vec3(0.13f, 0.36f, 0.52f) + velocityA * t;
        const glm::vec3 b = size * glm::vec3(0.47f, 0.57f, 0.19f) + velocityB * t;
        const shared::FluidSolid solid = solidCapsule(a, b, 0.11f * size.y, velocityA, velocityB);
        const auto emitters = s.emitters(step);
        ASSERT_TRUE(sparse->setEmitters(emitters).ok());
        ASSERT_TRUE(sparse->setSolids(std::span(&solid, 1)).ok());
        cpu.setSolids(std::span(&solid, 1));
        sparse->step();
        cpu.step(emitters);
    }
    SideBySide run;
    run.options = o;
    run.gpu = sparse->state();
    run.cpu = cpu.state();
    run.difference = fluid::difference(run.gpu, run.cpu);
    EXPECT_EQ(sparse->lastSharedFaceMismatches(), 0u);
    printDifference("sparse, 100 steps, swept capsule", run.difference);
    expectClose(run.difference, 1e-4, "sparse, 100 steps with a swept capsule");
    expectMovingAndFinite(run);
}

// The GPU's rebuild wants every brick the solids may reach (none was active, nothing is live), not
// grown by the dilation, beside an emitter's bricks, grown: brick for brick as the layout's twin
// (SparseBricks::wantSphere, dilate, then wantCapsule); every solid cell lies in an active brick.
TEST_F(SparseSolidsTest, TheRebuildWantsTheBricksTheSolidsReach) {
    const SolverOptions o = openOptions({64, 48, 48, 0.05f});
    auto sparse = makeSparse(ctx(), o, 4096, 8);
    ASSERT_TRUE(sparse);
    const std::vector<shared::FluidSolid> solids = {
        solidCapsule({0.6f, 0.9f, 1.1f}, {1.9f, 1.4f, 0.7f}, 0.12f, {1.0f, 0.0f, 0.0f},
                     {0.0f, 2.0f, 0.0f}),
        solidSphere({2.9f, 0.3f, 2.2f}, 0.2f), // past the high x side: cut off
        solidSphere({7.0f, 1.0f, 1.0f}, 0.3f), // wholly outside: nothing
    };
    ASSERT_TRUE(sparse->setSolids(solids).ok());
    const shared::FluidEmitter source =
        emitter({2.2f, 1.9f, 1.7f}, 0.15f, {0.0f, 1.0f, 0.0f}, 5.0f, {1.0f, 1.0f, 1.0f, 1.0f});
    ASSERT_TRUE(sparse->setEmitters(std::span(&source, 1)).ok());
    const float h = o.grid.cellSize;
    size_t previous = 0;
    for (uint32_t reach : {0u, fluid::kBrickSize}) {
        gpu::submitOneShot(
            ctx(), [&](VkCommandBuffer cmd) { sparse->recordRebuild(cmd, 1e-4f, 0.1f, reach); });
        sparse->finishRebuild(); // grown: the refused bricks get slots at the next rebuild
        gpu::submitOneShot(
            ctx(), [&](VkCommandBuffer cmd) { sparse->recordRebuild(cmd, 1e-4f, 0.1f, reach); });
        EXPECT_EQ(sparse->finishRebuild().refused, 0u);

        fluid::SparseBricks twin(sparse->layout().bricks(), 4096);
        twin.clearWanted();
        twin.wantSphere(glm::vec3(source.positionRadius) / h, source.positionRadius.w / h);
        twin.dilate(reach);
        for (const shared::FluidSolid& s : solids)
            twin.wantCapsule(glm::vec3(s.endA) / h, glm::vec3(s.endB) / h, s.endA.w / h);
        twin.commit();
        EXPECT_EQ(sparse->activeBricks(), twin.activeList()) << "reach " << reach;
        EXPECT_GT(twin.activeList().size(), previous + 20) << "reach " << reach;
        EXPECT_LT(twin.activeList().size(), 200u); // of 432
        previous = twin.activeList().size();

        const std::vector<uint8_t> active = sparse->activeCells();
        const std::vector<uint8_t> solid = fluid::solidCellMask(o.grid, solids);
        size_t solidCells = 0, outside = 0;
        for (size_t cell = 0; cell < solid.size(); ++cell)
            if (solid[cell]) {
                ++solidCells;
                outside += active[cell] ? 0 : 1;
            }
        EXPECT_GT(solidCells, 100u);
        EXPECT_EQ(outside, 0u) << "solid cells in inactive bricks";
    }
}

// The body keeps the bricks around it active and its air stirred as long as it moves: a grid with
// solids settles once no brick holds live pigment, whatever its bricks and speeds; with pigment it
// does not.
TEST_F(SparseSolidsTest, AGridWithSolidsSettlesOnItsPigmentAlone) {
    const SolverOptions o = openOptions({32, 32, 32, 0.05f});
    auto sparse = makeSparse(ctx(), o);
    ASSERT_TRUE(sparse);
    const shared::FluidSolid leg = solidCapsule({0.5f, 0.4f, 0.8f}, {1.1f, 0.9f, 0.8f}, 0.1f,
                                                {3.0f, 0.0f, 0.0f}, {4.0f, 1.0f, 0.0f});
    ASSERT_TRUE(sparse->setSolids(std::span(&leg, 1)).ok());
    const fluid::SettleRules rules{1e-4f, 0.0f, 0.1f};
    const gpu::Buffer unused = gpu::createBuffer(ctx(), 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                 gpu::MemoryUsage::Readback, "unused");
    auto frame = [&]() {
        gpu::submitOneShot(
            ctx(), [&](VkCommandBuffer cmd) { sparse->recordSceneStep(cmd, rules, nullptr); });
        return sparse->finishFrame(unused, true, true, rules);
    };
    fluid::SolverActivity a;
    for (int step = 0; step < 3; ++step)
        a = frame();
    EXPECT_GT(a.activeBricks, 0u);
    EXPECT_TRUE(a.settled) << "no pigment anywhere";
    const FieldState moved = sparse->state();
    EXPECT_GT(fluid::computeDiagnostics(o, moved).maxSpeed, 0.5) << "the solid moves the air";

    // A puff of pigment beside the leg: live.
    shared::FluidEmitter puff =
        emitter({0.8f, 1.0f, 0.8f}, 0.15f, {0.0f, 0.0f, 0.0f}, 20.0f, {1.0f, 1.0f, 1.0f, 1.0f});
    ASSERT_TRUE(sparse->setEmitters(std::span(&puff, 1)).ok());
    frame();
    ASSERT_TRUE(sparse->setEmitters({}).ok());
    a = frame();
    EXPECT_FALSE(a.settled) << "live pigment";
}

// The fighter's roundhouse kick through a band of smoke on every brick of a sparse domain, as on
// the dense GPU solver (test_fluid_gpu_solids.cpp): at most 1% of the pigment in the body's solid
// cells after every step, and the band's air set moving.
TEST_F(SparseSolidsTest, TheKickThroughACloudPushesItAndNeverHoldsPigmentInside) {
    const SolverOptions options = kickBandOptions();
    auto with = makeSparse(ctx(), options);
    auto without = makeSparse(ctx(), options);
    ASSERT_TRUE(with && without);
    for (SparseSmokeSolver* s : {with.get(), without.get()}) {
        activate(*s, [](glm::ivec3) { return true; });
        s->setState(kickBandCloud(options.grid));
    }
    const KickBandRun run = runKickThroughBand(
        options,
        [&](const std::vector<shared::FluidSolid>& solids) {
            ASSERT_TRUE(with->setSolids(solids).ok());
            with->step();
            without->step();
        },
        [&] { return with->state(); }, [&] { return without->state(); });
    std::printf("sparse kick through a band of smoke: at most %.2g of the pigment inside the "
                "body; the band's air at %.3f m/s (%.3f without the body)\n",
                run.largestInside, run.speed, run.stillSpeed);
    EXPECT_LE(run.largestInside, 0.01);
    EXPECT_GT(run.speed, 0.05);
    EXPECT_LT(run.stillSpeed, 1e-6);
}

} // namespace
} // namespace mfx::test
