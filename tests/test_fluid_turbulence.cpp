// The curl-noise turbulence force (fluid/reference/apply_turbulence.cpp,
// shaders/fluid/apply_turbulence.comp; docs/fluid.md, "applyTurbulence"): divergence-free by
// construction (its discrete divergence at rounding level, below what the pressure projection
// leaves), the GPU against the reference at times between the noise's layers, its time and its
// amplitude, and the scene keys that turn it on.
#include "core/scene/kinds/smoke_effect.h"
#include "core/scene/scene.h"
#include "fluid/field_compare.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/smoke_solver.h"
#include "tests/fluid_side_by_side.h"
#include "tests/fluid_test_util.h"
#include "tests/gpu_test.h"

#include <cmath>
#include <cstdio>

namespace mfx::test {
namespace {

// Options with turbulence alone (nothing else moves the air), on `boundaries`.
fluid::SolverOptions turbulenceOnly(fluid::SolverOptions o) {
    o.fade = o.drag = o.buoyancy = o.vorticity = o.viscosity = 0.0f;
    o.turbulence = 5.0f;
    o.turbulenceScale = 0.3f;
    o.turbulenceSpeed = 2.0f;
    return o;
}

double rms(const std::vector<float>& values) {
    double sum = 0.0;
    for (float v : values)
        sum += double(v) * double(v);
    return values.empty() ? 0.0 : std::sqrt(sum / double(values.size()));
}

// The divergence of a state's velocity relative to its speed: rms(div u) h / rms(u over faces),
// as the reference's computeDivergence gives it (1/s), times the cell size over the speed.
double relativeDivergence(const fluid::SolverOptions& options, const fluid::FieldState& state) {
    fluid::ReferenceSolver measure(options);
    measure.setState(state);
    measure.runStage(fluid::Stage::ComputeDivergence, {});
    std::vector<float> faces = state.velocityX;
    faces.insert(faces.end(), state.velocityY.begin(), state.velocityY.end());
    faces.insert(faces.end(), state.velocityZ.begin(), state.velocityZ.end());
    return rms(measure.state().divergence) * double(options.grid.cellSize) / rms(faces);
}

// From still air, the force alone: its velocity after one application (a multiple of curl psi).
fluid::FieldState turbulenceFromRest(const fluid::SolverOptions& options, double time) {
    fluid::ReferenceSolver cpu(options);
    cpu.setState(fluid::FieldState::zero(options.grid));
    cpu.setTime(time);
    cpu.runStage(fluid::Stage::ApplyTurbulence, {});
    return cpu.state();
}

using TurbulenceTest = GpuTest;

// Curl noise from rest is divergence-free to rounding in the reference (fp64, its state stored as
// fp32 as every state is) and on the GPU (fp32), on both boundary sets (walls, periodic, open): at
// the level an exact pressure solve leaves after projecting random velocity (the reference's
// conjugate gradient, where the open boundary lets it solve exactly), far below what the solver's
// own Jacobi projection leaves. The fp32 face values carry a relative rounding of 6e-8, which the
// divergence of a field with none inherits.
TEST_F(TurbulenceTest, ItsDivergenceIsAtRoundingLevelBelowTheProjectionsResidual) {
    for (const bool mixed : {false, true}) {
        const fluid::SolverOptions options =
            turbulenceOnly(mixed ? mixedBoundaryOptions() : closedBoxOptions());
        const fluid::FieldState cpu = turbulenceFromRest(options, 0.3);
        auto created = fluid::SmokeSolver::create(ctx(), options);
        ASSERT_TRUE(created) << created.error().message;
        fluid::SmokeSolver& gpu = *created.value();
        gpu.setState(fluid::FieldState::zero(options.grid));
        gpu.setTime(0.3);
        gpu.runStage(fluid::Stage::ApplyTurbulence);
        const fluid::FieldState onGpu = gpu.state();

        // The projection of random velocity: what it leaves of the divergence, the same measure.
        fluid::SolverOptions projected = options;
        projected.turbulence = 0.0f;
        fluid::ReferenceSolver solve(projected);
        solve.setState(randomState(options.grid, 77));
        solve.runStage(fluid::Stage::ComputeDivergence, {});
        solve.runStage(fluid::Stage::SolvePressure, {});
        solve.runStage(fluid::Stage::Project, {});
        const double jacobi = relativeDivergence(projected, solve.state());
        fluid::ReferenceSolver exact(projected);
        exact.setState(randomState(options.grid, 77));
        exact.computeDivergence();
        exact.solvePressureExact();
        exact.project();
        const double cg = relativeDivergence(projected, exact.state());

        const double reference = relativeDivergence(options, cpu);
        const double device = relativeDivergence(options, onGpu);
        std::printf("%s: rms speed %.3g m/s; relative divergence (rms div h / rms u): curl noise "
                    "%.3g (reference, fp64), %.3g (GPU, fp32); after projecting random velocity: "
                    "%.3g (%u Jacobi sweeps), %.3g (conjugate gradient to 1e-12)\n",
                    mixed ? "mixed boundaries" : "closed box",
                    rms(cpu.velocityX) + rms(cpu.velocityY) + rms(cpu.velocityZ), reference, device,
                    jacobi, options.jacobiIterations, cg);
        EXPECT_GT(rms(cpu.velocityX) + rms(cpu.velocityY) + rms(cpu.velocityZ), 0.01)
            << "the force moved the air";
        EXPECT_LT(reference, 1e-6);
        EXPECT_LT(device, 1e-6);
        EXPECT_LT(device, 1e-3 * jacobi);
        if (mixed) {
            EXPECT_LT(device, 10.0 * cg); // the exact solve's rounding level
        }
    }
}

// Between two of the noise's time layers (t speed = 0.6 and 7.45) and on a layer (t speed = 2):
// the GPU as the reference, 1e-5 relative L2, from random velocity on both boundary sets.
TEST_F(TurbulenceTest, GpuMatchesTheReferenceBetweenTimeLayers) {
    for (const bool mixed : {false, true})
        for (const double time : {0.3, 1.0, 3.725}) {
            const fluid::SolverOptions options =
                turbulenceOnly(mixed ? mixedBoundaryOptions() : closedBoxOptions());
            const fluid::FieldState input = randomState(options.grid, 5);
            auto created = fluid::SmokeSolver::create(ctx(), options);
            ASSERT_TRUE(created) << created.error().message;
            fluid::SmokeSolver& gpu = *created.value();
            gpu.setState(input);
            gpu.setTime(time);
            gpu.runStage(fluid::Stage::ApplyTurbulence);
            fluid::ReferenceSolver cpu(options);
            cpu.setState(input);
            cpu.setTime(time);
            cpu.runStage(fluid::Stage::ApplyTurbulence, {});
            const fluid::StateDifference d = fluid::difference(gpu.state(), cpu.state());
            expectClose(d, 1e-5,
                        std::string(mixed ? "mixed" : "closed") +
                            " at t = " + std::to_string(time));
            EXPECT_GT(fluid::difference(cpu.state(), input).velocity.relL2, 1e-3);
        }
}

// The noise changes with time at its speed (a new layer every 1 / speed seconds) and smoothly in
// between; the force is linear in the amplitude; a step moves the solver's time on by dt.
TEST(Turbulence, ChangesAtItsSpeedAndScalesWithItsAmplitude) {
    const fluid::SolverOptions options = turbulenceOnly(closedBoxOptions());
    const fluid::FieldState at = turbulenceFromRest(options, 1.0);
    const fluid::FieldState soon =
        turbulenceFromRest(options, 1.0 + 0.01 / double(options.turbulenceSpeed));
    const fluid::FieldState later =
        turbulenceFromRest(options, 1.0 + 1.0 / double(options.turbulenceSpeed));
    const double near = fluid::difference(soon, at).velocity.relL2;
    const double far = fluid::difference(later, at).velocity.relL2;
    std::printf("relative change of the force: %.3g after 1/100 of a layer, %.3g after a layer\n",
                near, far);
    EXPECT_LT(near, 0.01);
    EXPECT_GT(far, 0.5);

    fluid::SolverOptions doubled = options;
    doubled.turbulence *= 2.0f;
    const fluid::FieldState twice = turbulenceFromRest(doubled, 1.0);
    for (size_t i = 0; i < at.velocityY.size(); ++i)
        ASSERT_NEAR(twice.velocityY[i], 2.0f * at.velocityY[i], 1e-5f) << "face " << i;

    fluid::ReferenceSolver cpu(options);
    cpu.setState(fluid::FieldState::zero(options.grid));
    cpu.step({});
    cpu.step({});
    EXPECT_DOUBLE_EQ(cpu.time(), 2.0 * double(options.dt));
}

// The scene keys: they make the grid dense and reach the solver's options; refused on the sparse
// domain and out of range, naming the key.
TEST(Turbulence, SceneKeysMakeTheGridDenseAndReachTheSolver) {
    Result<scene::Scene> s = scene::parseScene(
        R"({"effects": [{"type": "smoke", "turbulence": 3, "turbulence_scale": 0.4,
                         "turbulence_speed": 0.5}]})",
        "turbulence.json");
    ASSERT_TRUE(s) << s.error().message;
    const scene::SmokeGridSpec& g = s.value().effects[0].as<scene::SmokeSpec>()->grid;
    EXPECT_EQ(g.domain, "dense");
    EXPECT_FLOAT_EQ(g.turbulence, 3.0f);
    EXPECT_FLOAT_EQ(g.turbulenceScale, 0.4f);
    EXPECT_FLOAT_EQ(g.turbulenceSpeed, 0.5f);

    const std::pair<const char*, const char*> bad[] = {
        {R"("domain": "sparse", "turbulence": 3)", "effects[0].turbulence: only for \"domain\""},
        {R"("turbulence": -1)", "effects[0].turbulence: -1 is outside"},
        {R"("turbulence_scale": 0)", "effects[0].turbulence_scale: 0 is outside"},
        {R"("turbulence_speed": 1e9)", "effects[0].turbulence_speed: "},
    };
    for (const auto& [keys, message] : bad) {
        Result<scene::Scene> refused = scene::parseScene(
            std::string(R"({"effects": [{"type": "smoke", )") + keys + "}]}", "bad.json");
        ASSERT_FALSE(refused) << keys;
        EXPECT_NE(refused.error().message.find(message), std::string::npos)
            << keys << ": " << refused.error().message;
    }
}

} // namespace
} // namespace mfx::test
