// Inputs shared by the solver tests: option sets covering every boundary kind, random field
// states and emitters, all deterministic.
#pragma once

#include "fluid/solver_options.h"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace mfx::test {

// The solver's names the fluid tests use unqualified.
using fluid::AdvectionScheme;
using fluid::Boundary;
using fluid::FieldState;
using fluid::GridShape;
using fluid::PressureSolver;
using fluid::SolverOptions;
using fluid::Storage;

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
    o.turbulence = 6.0f;
    o.turbulenceScale = 0.35f;
    o.turbulenceSpeed = 2.0f;
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
    o.turbulence = 4.0f;
    o.turbulenceScale = 0.5f;
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

// Velocity component c (0 x, 1 y, 2 z) of a state.
inline std::vector<float>& component(fluid::FieldState& s, int c) {
    return c == 0 ? s.velocityX : c == 1 ? s.velocityY : s.velocityZ;
}
inline const std::vector<float>& component(const fluid::FieldState& s, int c) {
    return c == 0 ? s.velocityX : c == 1 ? s.velocityY : s.velocityZ;
}

// A smooth velocity field (a few low Fourier modes per component, no symmetry), far from
// divergence-free: its divergence is smooth, the case multigrid's convergence rate is quoted for.
inline fluid::FieldState smoothState(const fluid::GridShape& g) {
    fluid::FieldState s = fluid::FieldState::zero(g);
    const double h = double(g.cellSize);
    const glm::dvec3 size = glm::dvec3(g.cellsX, g.cellsY, g.cellsZ) * h;
    for (int c = 0; c < 3; ++c) {
        const glm::uvec3 n = fluid::faceExtent(g, c);
        for (uint32_t k = 0; k < n.z; ++k)
            for (uint32_t j = 0; j < n.y; ++j)
                for (uint32_t i = 0; i < n.x; ++i) {
                    glm::dvec3 x = (glm::dvec3(i, j, k) + 0.5) * h;
                    x[c] -= 0.5 * h;
                    const glm::dvec3 t = 2.0 * std::numbers::pi * x / size;
                    const double value = std::sin(t.x + 0.3 * c) * std::cos(2.0 * t.y - 0.2) +
                                         0.5 * std::cos(t.z + t.x + c) + 0.2 * (c + 1);
                    component(s, c)[i + size_t(n.x) * (j + size_t(n.y) * k)] = float(value);
                }
    }
    return s;
}

// Boundary sets of the pressure-solver tests.
enum class Boundaries { Walls, Open, Periodic, Mixed };
inline constexpr Boundaries kAllBoundaries[] = {Boundaries::Walls, Boundaries::Open,
                                                Boundaries::Periodic, Boundaries::Mixed};

inline const char* boundariesName(Boundaries b) {
    switch (b) {
    case Boundaries::Walls:
        return "walls";
    case Boundaries::Open:
        return "open";
    case Boundaries::Periodic:
        return "periodic";
    case Boundaries::Mixed:
        return "mixed";
    }
    return "?";
}

// Pressure-solve options on `grid`, cold start: mixed is mixedBoundaryOptions' faces (x periodic,
// y no-slip walls, z open below and a free-slip wall above); the others put one kind on every face.
inline fluid::SolverOptions pressureOptions(fluid::GridShape grid, Boundaries boundaries,
                                            fluid::PressureSolver solver) {
    fluid::SolverOptions o = mixedBoundaryOptions(grid);
    o.pressureSolver = solver;
    o.warmStart = false;
    const fluid::Boundary uniform = boundaries == Boundaries::Walls  ? fluid::Boundary::WallFreeSlip
                                    : boundaries == Boundaries::Open ? fluid::Boundary::Open
                                                                     : fluid::Boundary::Periodic;
    if (boundaries != Boundaries::Mixed)
        for (fluid::FaceBoundary& f : o.boundaries)
            f = {uniform, glm::vec3(0.0f)};
    return o;
}

} // namespace mfx::test
