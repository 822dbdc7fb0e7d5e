// Inputs shared by the solver tests: option sets covering every boundary kind, random field
// states and emitters, all deterministic.
#pragma once

#include "fluid/solver_options.h"

#include <random>
#include <vector>

namespace mfx::test {

// Every feature on, every boundary kind present: x periodic, y no-slip walls (the top one moving),
// z open below and a free-slip wall above.
inline fluid::SolverOptions mixedBoundaryOptions(fluid::GridShape grid = {12, 10, 8, 0.1f}) {
    fluid::SolverOptions o;
    o.grid = grid;
    o.dt = 0.05f;
    o.integrator = fluid::Integrator::RK2;
    o.fade = 0.5f;
    o.drag = 0.7f;
    o.buoyancy = 1.5f;
    o.vorticity = 0.4f;
    o.viscosity = 0.02f;
    o.viscosityIterations = 7;
    o.jacobiIterations = 13;
    o.boundaries[fluid::FaceLowX].kind = fluid::Boundary::Periodic;
    o.boundaries[fluid::FaceHighX].kind = fluid::Boundary::Periodic;
    o.boundaries[fluid::FaceLowY].kind = fluid::Boundary::WallNoSlip;
    o.boundaries[fluid::FaceHighY].kind = fluid::Boundary::WallNoSlip;
    o.boundaries[fluid::FaceHighY].wallVelocity = {0.7f, 0.0f, -0.3f};
    o.boundaries[fluid::FaceLowZ].kind = fluid::Boundary::Open;
    o.boundaries[fluid::FaceHighZ].kind = fluid::Boundary::WallFreeSlip;
    return o;
}

// A closed box of free-slip walls with Euler back-tracing.
inline fluid::SolverOptions closedBoxOptions(fluid::GridShape grid = {9, 11, 7, 0.125f}) {
    fluid::SolverOptions o;
    o.grid = grid;
    o.dt = 0.04f;
    o.fade = 0.2f;
    o.buoyancy = 0.8f;
    o.vorticity = 0.3f;
    o.viscosity = 0.01f;
    o.viscosityIterations = 6;
    o.jacobiIterations = 20;
    return o;
}

// Random fields: velocities in [-1, 1], pressure and divergence in [-1, 1], pigment in [0, 1].
inline fluid::FieldState randomState(const fluid::GridShape& grid, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> signedValue(-1.0f, 1.0f), unit(0.0f, 1.0f);
    fluid::FieldState s = fluid::FieldState::zero(grid);
    for (auto* field : {&s.velocityX, &s.velocityY, &s.velocityZ, &s.pressure, &s.divergence})
        for (float& v : *field)
            v = signedValue(rng);
    for (float& v : s.pigment)
        v = unit(rng);
    return s;
}

inline shared::FluidEmitter emitter(glm::vec3 position, float radius, glm::vec3 velocity,
                                    float strength, glm::vec4 pigment) {
    return {glm::vec4(position, radius), glm::vec4(velocity, strength), pigment};
}

inline std::vector<shared::FluidEmitter> twoEmitters(const fluid::GridShape& g) {
    const glm::vec3 size = glm::vec3(g.cellsX, g.cellsY, g.cellsZ) * g.cellSize;
    return {emitter(size * glm::vec3(0.3f, 0.4f, 0.5f), 0.35f * size.y, {1.5f, 0.5f, 0.0f}, 8.0f,
                    {1.0f, 0.5f, 0.2f, 1.0f}),
            emitter(size * glm::vec3(0.7f, 0.6f, 0.4f), 0.25f * size.y, {-0.5f, 0.0f, 1.0f}, 20.0f,
                    {0.1f, 0.2f, 0.9f, 0.8f})};
}

} // namespace mfx::test
