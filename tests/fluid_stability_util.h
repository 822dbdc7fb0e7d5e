// The usual solver settings and emitters the stability tests' hard cases are multiples of, and a
// GPU run of many whole steps batched into command buffers (test_fluid_stability*.cpp).
#pragma once

#include "core/gpu/commands.h"
#include "fluid/smoke_solver.h"
#include "tests/fluid_test_util.h"

#include <algorithm>
#include <memory>
#include <vector>

// A namespace of its own: these Boundaries (the stability cases' boundary sets) would otherwise
// clash with fluid_test_util.h's (the pressure tests').
namespace mfx::test::stability {

// The usual settings the hard cases are multiples of.
inline constexpr float kUsualDt = 1.0f / 60.0f;
inline constexpr float kUsualVorticity = 0.3f;
inline constexpr float kUsualViscosity = 0.001f; // nominal: the usual options run inviscid
// Half SolverOptions' default of 20: each sweep is a dispatch (~0.1 ms on lavapipe whatever the
// grid), and the bounds hold for any number of cold-started sweeps (0 is a case of its own).
inline constexpr uint32_t kUsualJacobi = 10;
inline constexpr float kUsualSpeed = 2.0f; // the fastest emitter velocity component (usualEmitters)

// Non-cubic, so that a mix-up of axes cannot hide; 120 cells keep 2,000 CPU steps quick.
inline const fluid::GridShape kGrid{6, 5, 4, 0.2f};

// Closed: free-slip walls all round, Euler back-tracing. Mixed: every boundary kind (periodic x,
// still no-slip walls in y, open -z, free-slip +z) with RK2. PeriodicNoSlip: Mixed with the open
// face walled, a closed system for the strict energy check (only the source-free CFL cases).
enum class Boundaries { Closed, Mixed, PeriodicNoSlip };

inline fluid::SolverOptions usualOptions(fluid::GridShape grid, Boundaries boundaries) {
    fluid::SolverOptions o;
    o.grid = grid;
    o.dt = kUsualDt;
    // Buoyancy and vorticity stay 0 except where a case says: both add energy, which the energy
    // bounds exclude (the vorticity case has its own bound). Fade stays 0: the pigment ceiling
    // must hold without help.
    o.buoyancy = 0.0f;
    o.vorticity = 0.0f;
    // Viscosity off, as in SolverOptions: inviscid smoke has nothing but the numerics to damp it.
    o.viscosity = 0.0f;
    o.jacobiIterations = kUsualJacobi;
    o.warmStart = false; // the energy argument for the projection needs the cold start
    if (boundaries != Boundaries::Closed) {
        o.integrator = fluid::Integrator::RK2;
        o.boundaries[fluid::FaceLowX].kind = fluid::Boundary::Periodic;
        o.boundaries[fluid::FaceHighX].kind = fluid::Boundary::Periodic;
        // Still walls: a moving wall would be a source of energy.
        o.boundaries[fluid::FaceLowY].kind = fluid::Boundary::WallNoSlip;
        o.boundaries[fluid::FaceHighY].kind = fluid::Boundary::WallNoSlip;
        o.boundaries[fluid::FaceLowZ].kind =
            boundaries == Boundaries::Mixed ? fluid::Boundary::Open : fluid::Boundary::WallFreeSlip;
        o.boundaries[fluid::FaceHighZ].kind = fluid::Boundary::WallFreeSlip;
    }
    return o;
}

inline glm::vec3 domainSize(const fluid::GridShape& g) {
    return glm::vec3(g.cellsX, g.cellsY, g.cellsZ) * g.cellSize;
}

// Two overlapping emitters, placed relative to the domain; velocities scaled by `speedScale`. The
// fastest velocity component is kUsualSpeed * speedScale.
inline std::vector<shared::FluidEmitter> usualEmitters(const fluid::GridShape& g,
                                                       float speedScale) {
    const glm::vec3 size = domainSize(g);
    const float radius = 0.35f * std::max({size.x, size.y, size.z});
    return {emitter(size * glm::vec3(0.3f, 0.45f, 0.5f), radius,
                    speedScale * glm::vec3(kUsualSpeed, 1.0f, -0.5f), 8.0f,
                    {1.0f, 0.5f, 0.2f, 1.0f}),
            emitter(size * glm::vec3(0.7f, 0.55f, 0.4f), 0.8f * radius,
                    speedScale * glm::vec3(-1.0f, 0.0f, 1.5f), 20.0f, {0.1f, 0.2f, 0.9f, 0.8f})};
}

// The most whole steps GpuSimulation records into one command buffer.
inline constexpr uint32_t kStepsPerSubmit = 100;

class Simulation {
public:
    virtual ~Simulation() = default;
    virtual void advance(uint32_t steps) = 0;
    virtual fluid::FieldState state() = 0;
};

class GpuSimulation : public Simulation {
public:
    GpuSimulation(const gpu::Context& ctx, std::unique_ptr<fluid::SmokeSolver> solver)
        : ctx_(ctx), solver_(std::move(solver)) {}
    // Many whole steps in one command buffer. recordStep() writes the parameters uniform at record
    // time and tracks the ping-pong images as it records; the options and emitters do not change
    // here, so every write is the same block and recording n steps equals n step() calls.
    // At most kStepsPerSubmit steps per command buffer: the driver's memory for a recording grows
    // with its length.
    void advance(uint32_t steps) override {
        for (uint32_t done = 0; done < steps;) {
            const uint32_t batch = std::min(kStepsPerSubmit, steps - done);
            gpu::submitOneShot(ctx_, [&](VkCommandBuffer cmd) {
                for (uint32_t i = 0; i < batch; ++i)
                    solver_->recordStep(cmd);
            });
            done += batch;
        }
    }
    fluid::FieldState state() override { return solver_->state(); }

private:
    const gpu::Context& ctx_;
    std::unique_ptr<fluid::SmokeSolver> solver_;
};

} // namespace mfx::test::stability
