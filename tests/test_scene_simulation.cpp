// A scene's simulation: only what the scene calls for is allocated and dispatched, a smoke grid
// sleeps after its effects' windows and wakes for the next, a moving vertex's impulse lands where
// the CPU reference puts it with the segment's colour, and the frame rate does not change the
// smoke.
#include "core/anim/fighter.h"
#include "core/gpu/commands.h"
#include "core/scene/kinds/smoke_effect.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/smoke_solver.h"
#include "fluid/solver_options.h"
#include "sim/scene_simulation.h"
#include "tests/gpu_test.h"
#include "tests/moving_point.h"
#include "tests/scene_sim_util.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace mfx::test {
namespace {

using SceneSimulationTest = GpuTest;

bool ran(const sim::SimulationFrameStats& stats, const std::string& name) {
    for (const sim::PassRecord& p : stats.passes)
        if (p.name == name) return p.dispatches > 0;
    return false;
}

TEST_F(SceneSimulationTest, SpeedLinesAloneAllocateNoFluidAndDispatchNone) {
    const scene::Scene s =
        parseScene(R"({"output": {"frames": 6}, "effects": [{"type": "speed_lines"}]})");
    const anim::Character fighter = anim::makeFighter();
    auto sim = simulate(ctx(), s, fighter);
    ASSERT_TRUE(sim);
    EXPECT_TRUE(sim->smokeGrids().empty());
    EXPECT_EQ(sim->fluidBytes(), 0u);
    for (uint32_t f = 0; f < 6; ++f) {
        const sim::SimulationFrameStats stats = sim->runFrame(f);
        EXPECT_EQ(stats.fluidBytes, 0u);
        EXPECT_EQ(stats.fluidDispatches(), 0u);
        EXPECT_TRUE(ran(stats, "speed_lines#0/split"));
        EXPECT_EQ(stats.dispatches(), 1u); // the one trajectory pass
    }
}

// A smoke effect's solver keys reach its grid's solver options, named as the solver names them.
TEST_F(SceneSimulationTest, SmokeSolverKeysChooseTheGridsPressureAdvectionAndStorage) {
    EXPECT_EQ(scene::smokePressureSolvers().size(), 4u);
    for (const std::string& name : scene::smokePressureSolvers())
        EXPECT_TRUE(fluid::pressureSolverFromName(name)) << name;
    for (const std::string& name : scene::smokeAdvectionSchemes())
        EXPECT_TRUE(fluid::advectionFromName(name)) << name;
    for (const std::string& name : scene::smokeStorages())
        EXPECT_TRUE(fluid::storageFromName(name)) << name;
    const scene::Scene s = parseScene(R"({"output": {"frames": 2}, "effects": [
        {"type": "smoke", "bones": ["foot_r"], "grid": [16, 16, 16], "cell_size": 0.12,
         "pressure": "mgpcg", "advection": "bfecc", "storage": "fp16", "jacobi": 7}]})");
    const anim::Character fighter = anim::makeFighter();
    auto sim = simulate(ctx(), s, fighter);
    ASSERT_TRUE(sim);
    const fluid::SolverOptions& o = sim->smokeGrids()[0].grid.settings().options;
    EXPECT_EQ(o.pressureSolver, fluid::PressureSolver::MultigridPcg);
    EXPECT_EQ(o.advection, fluid::AdvectionScheme::Bfecc);
    EXPECT_EQ(o.storage, fluid::Storage::Float16);
    EXPECT_EQ(o.jacobiIterations, 7u);
    for (uint32_t f = 0; f < 2; ++f)
        sim->runFrame(f);
    const scene::Scene plain = parseScene(
        R"({"effects": [{"type": "smoke", "bones": ["foot_r"], "grid": [16, 16, 16]}]})");
    auto defaults = simulate(ctx(), plain, fighter);
    ASSERT_TRUE(defaults);
    const fluid::SolverOptions& d = defaults->smokeGrids()[0].grid.settings().options;
    EXPECT_EQ(d.pressureSolver, fluid::PressureSolver::Jacobi);
    EXPECT_EQ(d.advection, fluid::AdvectionScheme::SemiLagrangian);
    EXPECT_EQ(d.storage, fluid::Storage::Float32);
}

// Two smoke effects share one grid; the first lives for 0.3 s, the second from 1.6 s. In between
// the grid settles and must fall asleep (zero dispatches); it wakes when the second begins.
TEST_F(SceneSimulationTest, SmokeSleepsAfterItsWindowAndWakesForTheNext) {
    const scene::Scene s = parseScene(R"({
        "character": {"clip": "spin", "loop": true},
        "output": {"fps": 30, "frames": 60},
        "effects": [
            {"type": "smoke", "name": "first", "bones": ["hand_r"], "end": 0.3,
             "grid": [16, 16, 16], "cell_size": 0.15, "fade": 8, "drag": 4,
             "sleep_threshold": 0.002},
            {"type": "smoke", "name": "second", "bones": ["hand_l"], "start": 1.6,
             "grid": [16, 16, 16], "cell_size": 0.15, "fade": 8, "drag": 4,
             "sleep_threshold": 0.002}
        ]})");
    const anim::Character fighter = anim::makeFighter();
    auto sim = simulate(ctx(), s, fighter);
    ASSERT_TRUE(sim);
    ASSERT_EQ(sim->smokeGrids().size(), 1u); // shared
    EXPECT_GT(sim->fluidBytes(), 16u * 16u * 16u * 4u * 4u);
    int asleepFrom = -1, wokeAt = -1;
    for (uint32_t f = 0; f < 60; ++f) {
        const sim::SimulationFrameStats stats = sim->runFrame(f);
        const float t = stats.time;
        if (stats.grids[0].measured)
            std::printf("frame %u: largest alpha %.3g, speed %.3g m/s\n", f,
                        double(stats.grids[0].largestAlpha), double(stats.grids[0].largestSpeed));
        if (t <= 0.3f) {
            EXPECT_GT(stats.fluidDispatches(), 0u) << "frame " << f;
            EXPECT_TRUE(ran(stats, "smoke0/first/segment_emitters")) << "frame " << f;
        }
        if (t > 0.3f && t < 1.55f && stats.fluidDispatches() == 0 && asleepFrom < 0)
            asleepFrom = int(f);
        if (asleepFrom >= 0 && t < 1.55f) {
            EXPECT_EQ(stats.fluidDispatches(), 0u) << "frame " << f << " after sleeping";
        }
        if (t >= 1.6f - 1e-4f && wokeAt < 0 && stats.fluidDispatches() > 0) wokeAt = int(f);
    }
    std::printf("smoke window ended at frame 9; asleep from frame %d; woke at frame %d\n",
                asleepFrom, wokeAt);
    ASSERT_GE(asleepFrom, 0) << "the grid never went to sleep";
    EXPECT_LE(asleepFrom, 9 + 30); // within a second of the window's end
    EXPECT_EQ(wokeAt, 48);         // 1.6 s at 30 fps
}

TEST_F(SceneSimulationTest, OneMovingVertexPushesTheRightCellsLikeTheReference) {
    const anim::Character point = movingPoint();
    ASSERT_TRUE(anim::checkInvariants(point).ok());
    scene::Scene s = parseScene(R"({
        "character": {"source": "point.gltf", "start": 0.9},
        "stage": {"floor": false},
        "output": {"fps": 30, "frames": 2},
        "effects": [{"type": "smoke", "grid": [16, 12, 12], "cell_size": 0.05, "fade": 0,
                     "impulse_k": 0.8, "radius": 0.08, "strength": 20, "sub_samples": 4,
                     "colour": [0.2, 0.6, 0.9], "jacobi": 20, "steps_per_second": 30}]})");
    auto sim = simulate(ctx(), s, point);
    ASSERT_TRUE(sim);
    fluid::SmokeGrid& grid = sim->smokeGrids()[0].grid;
    sim->runFrame(0); // no extent yet: zero velocity, pigment only
    const fluid::FieldState before = grid.state();
    sim->runFrame(1);
    const fluid::FieldState after = grid.state();

    // The CPU reference, stepping from the same fields with the emitters the CPU twins make from
    // the CPU twin of the segment.
    const sim::SceneSimulation::TrajectoryEffect& effect = sim->trajectories()[0];
    const auto live = effect.queue->liveSegments();
    ASSERT_EQ(live.size(), 2u);
    const auto segment = effect.queue->readSegment(live[0]);
    fluid::CouplingParameters coupling;
    coupling.gridOrigin = grid.origin();
    coupling.radius = 0.08f;
    coupling.strength = 20.0f;
    coupling.samplesPerVertex = 5;
    const auto emitters = fluid::segmentEmitters(segment, coupling);
    ASSERT_EQ(emitters.size(), 5u);
    fluid::ReferenceSolver reference(grid.options());
    reference.setState(before);
    reference.step(emitters);
    const fluid::FieldState expected = reference.state();

    double maxDiff = 0.0, maxValue = 0.0;
    for (size_t i = 0; i < after.velocityX.size(); ++i) {
        maxDiff = std::max(maxDiff, double(std::abs(after.velocityX[i] - expected.velocityX[i])));
        maxValue = std::max(maxValue, double(std::abs(expected.velocityX[i])));
    }
    std::printf("one vertex at 1.5 m/s (k = 0.8): largest x velocity %.4f m/s, GPU vs CPU %.3g\n",
                maxValue, maxDiff);
    EXPECT_LE(maxDiff, 1e-4 * maxValue);
    // Direction and magnitude: the pushed faces move along +x, at most k times the vertex's speed,
    // and the strongest push lies on the vertex's path (y = 0.6, z = 0 in the world).
    EXPECT_GT(maxValue, 0.3 * 0.8 * 1.5);
    EXPECT_LE(maxValue, 0.8 * 1.5 * 1.001);
    const fluid::GridShape& shape = grid.options().grid;
    const glm::uvec3 n(shape.cellsX, shape.cellsY, shape.cellsZ);
    size_t strongest = 0;
    for (size_t i = 0; i < after.velocityX.size(); ++i)
        if (after.velocityX[i] > after.velocityX[strongest]) strongest = i;
    const size_t fx = strongest % (n.x + 1), fy = (strongest / (n.x + 1)) % n.y,
                 fz = strongest / (size_t(n.x + 1) * n.y);
    const glm::vec3 world =
        grid.origin() + glm::vec3(float(fx), float(fy) + 0.5f, float(fz) + 0.5f) * shape.cellSize;
    EXPECT_NEAR(world.y, 0.6f, 0.08f + shape.cellSize);
    EXPECT_NEAR(world.z, 0.0f, 0.08f + shape.cellSize);
    float sideways = 0.0f;
    for (float v : after.velocityY)
        sideways = std::max(sideways, std::abs(v));
    EXPECT_LT(sideways, 0.5f * float(maxValue)); // mostly along x (projection adds a little)

    // Pigment: the segment's colour wherever the smoke is.
    size_t coloured = 0;
    for (size_t c = 0; c < after.pigment.size() / 4; ++c) {
        const float a = after.pigment[c * 4 + 3];
        if (a < 0.05f) continue;
        ++coloured;
        EXPECT_NEAR(after.pigment[c * 4 + 0] / a, 0.2f, 1e-3f);
        EXPECT_NEAR(after.pigment[c * 4 + 1] / a, 0.6f, 1e-3f);
        EXPECT_NEAR(after.pigment[c * 4 + 2] / a, 0.9f, 1e-3f);
    }
    EXPECT_GT(coloured, 0u);
}

// Smoke emitted from points spread over the surface instead of the vertices.
TEST_F(SceneSimulationTest, SurfaceEmissionFeedsTheGrid) {
    const scene::Scene s = parseScene(R"({
        "output": {"frames": 4},
        "effects": [{"type": "smoke", "bones": ["foot_r", "toe_r"], "emission": "surface",
                     "surface_step": 0.01, "grid": [12, 12, 12], "cell_size": 0.15,
                     "max_emitters": 64}]})");
    const anim::Character fighter = anim::makeFighter();
    auto sim = simulate(ctx(), s, fighter);
    ASSERT_TRUE(sim);
    const auto& effect = sim->trajectories()[0];
    EXPECT_EQ(effect.source.vertices.size(), effect.surface.samples);
    EXPECT_GT(effect.surface.samples, 300u); // at 1 cm, more points than the foot has vertices
    uint32_t emitters = 0;
    for (uint32_t f = 0; f < 4; ++f)
        emitters += sim->runFrame(f).grids[0].emitters;
    EXPECT_GT(emitters, 0u);
    const fluid::FieldState state = sim->smokeGrids()[0].grid.state();
    double pigment = 0.0;
    for (size_t c = 0; c < state.pigment.size() / 4; ++c)
        pigment += double(state.pigment[c * 4 + 3]);
    EXPECT_GT(pigment, 0.01);
}

// A grid that follows: the fields move by whole cells the other way, what comes in is 0.
TEST_F(SceneSimulationTest, ShiftMovesEveryFieldByWholeCells) {
    fluid::SolverOptions options;
    options.grid = {7, 5, 6, 0.1f};
    auto solver = fluid::SmokeSolver::create(ctx(), options);
    ASSERT_TRUE(solver.ok()) << solver.error().message;
    fluid::FieldState before = fluid::FieldState::zero(options.grid);
    uint32_t seed = 1;
    auto next = [&]() { return float((seed = seed * 1664525u + 1013904223u) >> 8) / 16777216.0f; };
    for (float& v : before.velocityX)
        v = next();
    for (float& v : before.velocityY)
        v = next();
    for (float& v : before.velocityZ)
        v = next();
    for (float& v : before.pressure)
        v = next();
    for (float& v : before.pigment)
        v = next();
    solver.value()->setState(before);
    const glm::ivec3 shift(2, 0, -1);
    gpu::submitOneShot(ctx(),
                       [&](VkCommandBuffer cmd) { solver.value()->recordShift(cmd, shift); });
    const fluid::FieldState after = solver.value()->state();
    auto check = [&](const std::vector<float>& old, const std::vector<float>& now, glm::ivec3 n,
                     int channels, const char* what) {
        for (int z = 0; z < n.z; ++z)
            for (int y = 0; y < n.y; ++y)
                for (int x = 0; x < n.x; ++x) {
                    const glm::ivec3 from = glm::ivec3(x, y, z) + shift;
                    const bool inside = glm::all(glm::greaterThanEqual(from, glm::ivec3(0))) &&
                                        glm::all(glm::lessThan(from, n));
                    for (int k = 0; k < channels; ++k) {
                        const size_t i = size_t(((z * n.y + y) * n.x + x) * channels + k);
                        const float expected =
                            inside ? old[size_t(
                                         ((from.z * n.y + from.y) * n.x + from.x) * channels + k)]
                                   : 0.0f;
                        ASSERT_EQ(now[i], expected) << what << " at " << x << "," << y << "," << z;
                    }
                }
    };
    const glm::ivec3 cells(7, 5, 6);
    check(before.velocityX, after.velocityX, cells + glm::ivec3(1, 0, 0), 1, "velocity x");
    check(before.velocityY, after.velocityY, cells + glm::ivec3(0, 1, 0), 1, "velocity y");
    check(before.velocityZ, after.velocityZ, cells + glm::ivec3(0, 0, 1), 1, "velocity z");
    check(before.pressure, after.pressure, cells, 1, "pressure");
    check(before.pigment, after.pigment, cells, 4, "pigment");
}

// With "follow", the grid keeps its place relative to a character walking along x (1.5 m/s),
// and the smoke already made stays where it was in the world.
TEST_F(SceneSimulationTest, GridFollowsTheCharacter) {
    const anim::Character point = movingPoint();
    scene::Scene s = parseScene(R"({
        "character": {"source": "point.gltf"},
        "output": {"fps": 30, "frames": 31},
        "effects": [{"type": "smoke", "grid": [16, 8, 8], "cell_size": 0.1, "fade": 0,
                     "drag": 0, "follow": true, "steps_per_second": 30, "end": 0.6}]})");
    auto sim = simulate(ctx(), s, point);
    ASSERT_TRUE(sim);
    const glm::vec3 start = sim->smokeGrids()[0].grid.origin();
    uint32_t shifts = 0;
    for (uint32_t f = 0; f < 31; ++f) {
        const auto stats = sim->runFrame(f);
        for (const auto& p : stats.passes)
            shifts += p.name == "smoke0/shift" ? 1 : 0;
    }
    const glm::vec3 moved = sim->smokeGrids()[0].grid.origin() - start;
    // 1.5 m in 1 s: the grid moved with it, to the nearest cell.
    EXPECT_NEAR(moved.x, 1.5f, 0.1f);
    EXPECT_EQ(moved.y, 0.0f);
    EXPECT_NEAR(moved.z, 0.0f, 1e-6f);
    EXPECT_GE(shifts, 8u); // about one a frame while it is awake (0.9 m in its window: 9 cells)
}

struct Totals {
    double pigment = 0.0;
    glm::dvec3 momentum{0.0};
};

Totals runAt(const gpu::Context& ctx, float fps, float stepsPerSecond) {
    const uint32_t frames = uint32_t(std::lround(0.8f * fps)) + 1; // the last at t = 0.8 s
    scene::Scene s = parseScene(R"({
        "character": {"clip": "roundhouse_kick"},
        "effects": [{"type": "smoke", "bones": ["foot_r", "toe_r"], "grid": [24, 24, 24],
                     "cell_size": 0.08, "fade": 0.5, "radius": 0.1}]})");
    s.output.fps = fps;
    s.output.frames = frames;
    s.effects[0].as<scene::SmokeSpec>()->grid.stepsPerSecond = stepsPerSecond;
    const anim::Character fighter = anim::makeFighter();
    auto sim = simulate(ctx, s, fighter);
    Totals totals;
    if (!sim) return totals;
    for (uint32_t f = 0; f < frames; ++f)
        sim->runFrame(f);
    const fluid::FieldState state = sim->smokeGrids()[0].grid.state();
    for (size_t c = 0; c < state.pigment.size() / 4; ++c)
        totals.pigment += double(state.pigment[c * 4 + 3]);
    for (float v : state.velocityX)
        totals.momentum.x += double(v);
    for (float v : state.velocityY)
        totals.momentum.y += double(v);
    for (float v : state.velocityZ)
        totals.momentum.z += double(v);
    return totals;
}

// The grid steps at 60 steps per second whatever the frame rate (two steps per frame at 30 fps),
// and its smoke effects' segments follow the steps, so the two runs simulate the same smoke.
// Stepping once per frame instead (steps_per_second 30) is printed for comparison: the splat's
// pull saturates and the advection's interpolation differs, so there the frame rate shows
// (about 10% more pigment at 30 fps than at 60 for this scene).
TEST_F(SceneSimulationTest, ThirtyAndSixtyFramesPerSecondAgree) {
    const Totals a = runAt(ctx(), 30.0f, 60.0f), b = runAt(ctx(), 60.0f, 60.0f);
    const double pigment = std::abs(a.pigment - b.pigment) / std::max(a.pigment, b.pigment);
    const double momentum = glm::length(a.momentum - b.momentum) /
                            std::max(glm::length(a.momentum), glm::length(b.momentum));
    std::printf("after 0.8 s: pigment %.4g (30 fps) vs %.4g (60 fps), %.2f%% apart; momentum "
                "|%.4g| vs |%.4g|, %.2f%% apart\n",
                a.pigment, b.pigment, 100.0 * pigment, glm::length(a.momentum),
                glm::length(b.momentum), 100.0 * momentum);
    const Totals once = runAt(ctx(), 30.0f, 30.0f);
    std::printf("one step per frame at 30 fps instead: pigment %.4g (%.1f%% from 60 fps), "
                "momentum |%.4g|\n",
                once.pigment, 100.0 * std::abs(once.pigment - b.pigment) / b.pigment,
                glm::length(once.momentum));
    EXPECT_GT(a.pigment, 1.0);
    EXPECT_GT(glm::length(a.momentum), 1.0);
    EXPECT_LT(pigment, 0.10);
    EXPECT_LT(momentum, 0.10);
}

} // namespace
} // namespace mfx::test
