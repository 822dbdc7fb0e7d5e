// The CPU reference of the smoke solver, on Eigen, in double precision: the yardstick the GPU
// solver is compared against, stage by stage. Each stage is a member function in a file of its
// own, named like the compute shader of the same stage (fluid/reference/advect_velocity.cpp ↔
// shaders/advect_velocity.comp), and follows docs/fluid.md exactly. Clear before fast.
//
// Stam, "Stable Fluids" (SIGGRAPH 1999) for the semi-Lagrangian advection and projection;
// Bridson, "Fluid Simulation for Computer Graphics" (2nd ed., 2015), ch. 2-5, for the MAC grid,
// its boundary conditions and the pressure matrix; Fedkiw, Stam, Jensen, "Visual Simulation of
// Smoke" (SIGGRAPH 2001), eqs. 9-11, for vorticity confinement.
#pragma once

#include "fluid/solver_options.h"

#include <cmath>
#include <Eigen/Core>
#include <array>
#include <glm/glm.hpp>
#include <span>

namespace mfx::fluid {

// Scalar diagnostics of a field state (docs/fluid.md, "Diagnostics").
struct Diagnostics {
    double maxDivergence = 0.0; // max |div u| over cells, 1/seconds
    double rmsDivergence = 0.0;
    double kineticEnergy = 0.0;   // 0.5 * sum over faces of u^2 * h^3
    glm::dvec4 totalPigment{0.0}; // sum over cells of pigment * h^3, per channel
    double maxPigment = 0.0;      // largest pigment channel value in any cell
    double maxSpeed = 0.0;        // max over cells of |cell-centred velocity|
    double cfl = 0.0;             // max |face velocity| * dt / h (per sub-step)
    uint64_t nonFinite = 0;       // NaN or Inf values in any field
};

// Diagnostics of `state` under `options` (dt and boundaries matter).
Diagnostics computeDiagnostics(const SolverOptions& options, const FieldState& state);

class ReferenceSolver {
public:
    // `options` must have passed validateOptions().
    explicit ReferenceSolver(const SolverOptions& options);

    void setState(const FieldState& state);
    FieldState state() const;
    const SolverOptions& options() const { return options_; }

    // One whole step: every stage of kStepOrder, `substeps` times. Emitters must have passed
    // validateEmitters().
    void step(std::span<const shared::FluidEmitter> emitters);
    // One stage alone, with the sub-step dt.
    void runStage(Stage stage, std::span<const shared::FluidEmitter> emitters);

    // The stages (docs/fluid.md). Each reads and writes the solver's fields.
    void splatImpulses(std::span<const shared::FluidEmitter> emitters);
    void advectVelocity();
    void advectPigment();
    void applyBuoyancy();
    void vorticityConfinement();
    void diffuseViscosity();
    void applyBoundaries();
    void computeDivergence();
    void solvePressure();      // Jacobi, options().jacobiIterations sweeps
    void solvePressureExact(); // Eigen's conjugate gradient to 1e-12 relative residual
    void project();

    // --- Grid access shared by the stages (fluid/reference/grid_access.cpp) ------------------
    // Advection's output rule (docs/fluid.md, steps 2 and 3): a magnitude below 1e-30 becomes 0.
    static double flushTiny(double v) { return std::abs(v) < kFlushBelow ? 0.0 : v; }
    static constexpr double kFlushBelow = 1.0e-30;
    // Value of velocity component `c` at integer face index `index`, which may lie outside the
    // array: periodic axes wrap, others clamp, and a no-slip wall mirrors tangential components
    // about its wall velocity.
    double fetchFace(int c, const Eigen::ArrayXd& field, glm::ivec3 index) const;
    // Cell-centred field value at a possibly out-of-range cell: wrap or clamp.
    double fetchCell(const Eigen::ArrayXd& field, glm::ivec3 index, int channels = 1,
                     int channel = 0) const;
    // Trilinear sample of component `c` / of a cell field at world position `x`.
    double sampleFace(int c, const Eigen::ArrayXd& field, glm::dvec3 x) const;
    double sampleCell(const Eigen::ArrayXd& field, glm::dvec3 x, int channels = 1,
                      int channel = 0) const;
    glm::dvec3 velocityAt(glm::dvec3 x) const; // from the current velocity
    glm::dvec3 clampToDomain(glm::dvec3 x) const;
    glm::dvec3 backTrace(glm::dvec3 x) const;
    glm::dvec3 facePosition(int c, glm::ivec3 index) const;
    glm::dvec3 cellCentre(glm::ivec3 index) const;
    // True for faces of component c lying on a wall the component is normal to.
    bool wallNormalFace(int c, glm::ivec3 index) const;
    size_t faceIndex(int c, glm::ivec3 index) const;
    size_t cellIndex(glm::ivec3 index) const;
    glm::ivec3 faceCount(int c) const;
    glm::ivec3 cellCount() const { return cells_; }

private:
    Boundary boundary(int axis, bool high) const {
        return options_.boundaries[2 * axis + high].kind;
    }
    double dt() const { return double(options_.substepDt()); }

    SolverOptions options_;
    glm::ivec3 cells_;
    double h_;
    std::array<Eigen::ArrayXd, 3> velocity_;
    Eigen::ArrayXd pressure_;
    Eigen::ArrayXd divergence_;
    Eigen::ArrayXd pigment_; // RGBA interleaved
};

} // namespace mfx::fluid
