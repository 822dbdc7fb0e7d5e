// The GPU solver and the CPU reference run side by side: a scenario's steps from the same start
// with the same emitters, and how far apart the two end. The 100-step comparisons of every solver
// variant (pressure solvers, advection schemes, fp16 storage, each scenario) use it.
#pragma once

#include "core/gpu/context.h"
#include "fluid/field_compare.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/scenarios.h"
#include "fluid/smoke_solver.h"

#include <functional>
#include <gtest/gtest.h>
#include <span>

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
