// The GPU solver and the CPU reference run side by side: a scenario's steps from the same start
// with the same emitters, and how far apart the two end. The 100-step comparisons of every solver
// variant (pressure solvers, advection schemes, fp16 storage, each scenario) use it.
#pragma once

#include "core/gpu/context.h"
#include "fluid/field_compare.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/scenarios.h"
#include "fluid/smoke_solver.h"

#include <cstdio>
#include <functional>
#include <gtest/gtest.h>
#include <span>
#include <string>

namespace mfx::test {

struct SideBySide {
    fluid::SolverOptions options; // the scenario's, as adjusted
    fluid::FieldState gpu, cpu;   // after the last step
    fluid::StateDifference difference;
};

// `steps` steps of scenario `name` at `cells`, its options changed by `adjust` (if given), on the
// GPU solver and on the CPU reference. A scenario or solver that cannot be made fails the test
// fatally (check HasFatalFailure() after the call).
inline void runSideBySide(const gpu::Context& ctx, const char* name, glm::uvec3 cells,
                          uint32_t steps, const std::function<void(fluid::SolverOptions&)>& adjust,
                          SideBySide& out) {
    auto scenario = fluid::makeScenario(name, cells);
    ASSERT_TRUE(scenario.ok()) << scenario.error().message;
    const fluid::Scenario& s = scenario.value();
    out.options = s.options;
    if (adjust) adjust(out.options);
    auto created = fluid::SmokeSolver::create(ctx, out.options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    fluid::SmokeSolver& gpu = *created.value();
    fluid::ReferenceSolver cpu(out.options);
    gpu.setState(s.initial);
    cpu.setState(s.initial);
    for (uint32_t step = 0; step < steps; ++step) {
        const auto emitters = s.emitters(step);
        ASSERT_TRUE(gpu.setEmitters(emitters).ok());
        gpu.step();
        cpu.step(emitters);
    }
    out.gpu = gpu.state();
    out.cpu = cpu.state();
    out.difference = fluid::difference(out.gpu, out.cpu);
}

// Each field's relative L2 difference at most `bound`, `what` naming the comparison.
inline void expectClose(const fluid::StateDifference& d, double bound, const std::string& what) {
    EXPECT_LE(d.velocity.relL2, bound)
        << what << ": velocity (max abs " << d.velocity.maxAbs << ")";
    EXPECT_LE(d.pressure.relL2, bound)
        << what << ": pressure (max abs " << d.pressure.maxAbs << ")";
    EXPECT_LE(d.divergence.relL2, bound)
        << what << ": divergence (max abs " << d.divergence.maxAbs << ")";
    EXPECT_LE(d.pigment.relL2, bound) << what << ": pigment (max abs " << d.pigment.maxAbs << ")";
}

// The comparison's line in the test log: "  <label>: velocity ..., pressure ..., ...".
inline void printDifference(const std::string& label, const fluid::StateDifference& d) {
    std::printf("  %s: velocity %.3g, pressure %.3g, pigment %.3g, divergence %.3g\n",
                label.c_str(), d.velocity.relL2, d.pressure.relL2, d.pigment.relL2,
                d.divergence.relL2);
}

// What every many-step comparison checks besides its bounds: the reference's smoke still moves
// (kinetic energy above 1e-6) and the GPU's state is finite.
inline void expectMovingAndFinite(const SideBySide& run) {
    EXPECT_GT(fluid::computeDiagnostics(run.options, run.cpu).kineticEnergy, 1e-6);
    EXPECT_EQ(fluid::computeDiagnostics(run.options, run.gpu).nonFinite, 0u);
}

// One stage alone from the same state `input` and `emitters`, on the GPU solver and on the CPU
// reference: their states after it (and the pressure solvers' iteration counts). A solver that
// cannot be made, or refuses the emitters, fails the test and leaves `ok` false.
struct StageSideBySide {
    bool ok = false;
    fluid::FieldState gpu, cpu;
    uint32_t gpuIterations = 0, cpuIterations = 0;
};
inline StageSideBySide runStageSideBySide(const gpu::Context& ctx,
                                          const fluid::SolverOptions& options,
                                          const fluid::FieldState& input, fluid::Stage stage,
                                          std::span<const shared::FluidEmitter> emitters = {}) {
    StageSideBySide out;
    auto created = fluid::SmokeSolver::create(ctx, options);
    EXPECT_TRUE(created.ok()) << created.error().message;
    if (!created.ok()) return out;
    fluid::SmokeSolver& gpu = *created.value();
    gpu.setState(input);
    const Status set = gpu.setEmitters(emitters);
    EXPECT_TRUE(set.ok()) << set.error().message;
    if (!set.ok()) return out;
    gpu.runStage(stage);
    fluid::ReferenceSolver cpu(options);
    cpu.setState(input);
    cpu.runStage(stage, emitters);
    out.gpu = gpu.state();
    out.cpu = cpu.state();
    out.gpuIterations = gpu.lastPressureIterations();
    out.cpuIterations = cpu.pressureIterations();
    out.ok = true;
    return out;
}

} // namespace mfx::test
