// The CPU reference of the smoke solver, on Eigen, in double precision: the yardstick the GPU
// solver is compared against, stage by stage. Each stage is a member function in a file of its
// own, named like the compute shader of the same stage (fluid/reference/advect_velocity.cpp ↔
// shaders/fluid/advect_velocity.comp), and follows docs/fluid.md exactly. Clear before fast.
//
// Stam, "Stable Fluids" (SIGGRAPH 1999) for the semi-Lagrangian advection and projection;
// Bridson, "Fluid Simulation for Computer Graphics" (2nd ed., 2015), ch. 2-5, for the MAC grid,
// its boundary conditions and the pressure matrix; Fedkiw, Stam, Jensen, "Visual Simulation of
// Smoke" (SIGGRAPH 2001), eqs. 9-11, for vorticity confinement. The accuracy options (red-black
// Gauss-Seidel, multigrid, MGPCG, MacCormack, BFECC, fp16 storage) cite their own sources in their
// files and in docs/fluid.md, "Accuracy options".
#pragma once

#include "fluid/solver_options.h"

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <utility>
#include <vector>

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

    // With Storage::Float16 the stored fields are rounded to half precision on the way in.
    void setState(const FieldState& state);
    FieldState state() const;
    // Seconds of simulation the steps have covered (step() adds dt after its sub-steps): the
    // turbulence's noise time. runStage reads it and leaves it.
    double time() const { return time_; }
    void setTime(double seconds) { time_ = seconds; }
    const SolverOptions& options() const { return options_; }

    // One whole step: every stage of stepOrder(), `substeps` times. Emitters must have passed
    // validateEmitters().
    void step(std::span<const shared::FluidEmitter> emitters);
    // One stage alone, with the sub-step dt; with Storage::Float16, velocity, pressure and pigment
    // are rounded to half precision after it (the member functions below do not round).
    void runStage(Stage stage, std::span<const shared::FluidEmitter> emitters);

    // The stages (docs/fluid.md). Each reads and writes the solver's fields.
    void splatImpulses(std::span<const shared::FluidEmitter> emitters);
    void advectVelocity();
    void advectPigment();
    void applyBuoyancy();
    void vorticityConfinement();
    void applyTurbulence(); // at time(): the step's start
    void diffuseViscosity();
    void applyBoundaries();
    void computeDivergence();
    void solvePressure();      // by options().pressureSolver (docs/fluid.md, "Accuracy options")
    void solvePressureExact(); // Eigen's conjugate gradient to 1e-12 relative residual
    void project();

    // --- The sparse domain (sparse_domain.cpp; docs/fluid.md, "Sparse domain") ---------------
    // Restricts the solver to the cells flagged in `activeCells` (one byte per cell, x fastest;
    // empty: every cell, the dense solver). What is not stored on the sparse grid is 0: a face
    // with no active cell beside it, and velocity, pressure, divergence and pigment of every
    // inactive cell; setState, setActiveCells and each stage run by runStage or step leave them
    // 0, and the Jacobi pressure sweeps hold inactive cells at p = 0. When the active cells
    // change, a face keeps its value only if a cell beside it is active before and after (the
    // sparse grid's activation), and the solids are marked again in the new cells (only stored
    // cells are solid). The options must pass
    // validateSparseOptions (std::invalid_argument otherwise, or when the size is wrong).
    void setActiveCells(std::vector<uint8_t> activeCells);
    // Whether cell q (inside the grid) is active, and whether face q of component c is stored.
    bool cellActive(glm::ivec3 q) const;
    bool faceStored(int c, glm::ivec3 q) const;

    // --- Solids (mark_solids.cpp; docs/fluid.md, "Solids") ------------------------------------
    // The moving solids of the steps from now on (each a capsule where the steps end, with its
    // ends' velocities; empty: none, the solver exactly as without). Marked at once and again at
    // the start of every sub-step of step(). std::invalid_argument when validateSolids or
    // validateSolidOptions refuses them.
    void setSolids(std::span<const shared::FluidSolid> solids);
    // The solid cells and faces of the current solids; solid faces set to the solids' velocity
    // and solid cells' pigment to 0.
    void markSolids();
    bool hasSolids() const { return !solidCells_.empty(); }
    // Whether cell q (inside the grid) is solid, and whether face q of component c is (a cell
    // beside it is solid; never a wall-normal face).
    bool solidCell(glm::ivec3 q) const;
    bool solidFace(int c, glm::ivec3 q) const;
    // The trilinear sample of a cell field at x from the fluid cells alone: the weights of solid
    // cells dropped and the rest renormalised, 0 when all eight are solid; the plain sample where
    // none is.
    double sampleCellOutsideSolids(const Eigen::ArrayXd& field, glm::dvec3 x, int channels = 1,
                                   int channel = 0) const;

    // --- Measuring the pressure solve ---------------------------------------------------------
    // The relative residual ||b - A p|| / ||b|| of the pressure equation A p = b for the current
    // pressure and divergence: (A p)_cell = sum over counted neighbours of (p - p_n) and
    // b = -h² div (docs/fluid.md, step 10). Without an open face A is singular and b is made
    // mean-free first (its part in the range of A). 0 when b is 0. After project(), the divergence
    // left is -(b - A p) / h²: this is also ||div after|| / ||div before||.
    double pressureResidual() const;
    // When on, solvePressure() records the relative residual before it starts and after every
    // sweep (Jacobi, red-black), V-cycle (multigrid) or iteration (MGPCG: CG's own residual).
    // Off by default: for the sweeps it costs one residual evaluation each.
    void setRecordResidualHistory(bool record) { recordHistory_ = record; }
    const std::vector<double>& residualHistory() const { return residualHistory_; }
    // Sweeps, V-cycles or CG iterations the last solvePressure() ran.
    uint32_t pressureIterations() const { return pressureIterations_; }

    // The nearest IEEE binary16 value to v (round to nearest, ties to even; overflow to +-inf,
    // NaN stays NaN), as a double: what Storage::Float16 keeps of a value.
    static double roundToHalf(double v);
    static void roundToHalf(Eigen::ArrayXd& values); // each value, in place

    // --- Grid access shared by the stages (fluid/reference/grid_access.cpp) ------------------
    // Advection's output rule (docs/fluid.md, steps 2 and 3): a magnitude below 1e-30 becomes 0.
    static double flushTiny(double v) { return std::abs(v) < kFlushBelow ? 0.0 : v; }
    static constexpr double kFlushBelow = 1.0e-30;
    // Value of velocity component `c` at integer face index `index`, which may lie outside the
    // array: periodic axes wrap, others clamp, and a no-slip wall mirrors tangential components
    // about its wall velocity.
    double fetchFace(int c, const Eigen::ArrayXd& field, glm::ivec3 index) const;
    // A possibly out-of-range cell brought into the grid: wrapped on periodic axes, clamped on
    // others (what fetchCell reads).
    glm::ivec3 resolveCell(glm::ivec3 index) const;
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
    // The same trace over `interval` instead of the sub-step dt; a negative interval traces
    // forwards (the reverse step of MacCormack and BFECC).
    glm::dvec3 backTrace(glm::dvec3 x, double interval) const;
    // Smallest and largest of the 8 values sampleFace / sampleCell interpolates from at x (the
    // limiter's range).
    glm::dvec2 sampleFaceRange(int c, const Eigen::ArrayXd& field, glm::dvec3 x) const;
    glm::dvec2 sampleCellRange(const Eigen::ArrayXd& field, glm::dvec3 x, int channels = 1,
                               int channel = 0) const;
    glm::dvec3 facePosition(int c, glm::ivec3 index) const;
    glm::dvec3 cellCentre(glm::ivec3 index) const;
    // True for faces of component c lying on a wall the component is normal to.
    bool wallNormalFace(int c, glm::ivec3 index) const;
    size_t faceIndex(int c, glm::ivec3 index) const;
    size_t cellIndex(glm::ivec3 index) const;
    glm::ivec3 faceCount(int c) const;
    // Calls visit(c, q) for every face q of every component c: x faces, then y, then z, each x
    // fastest (the order every face loop of the reference runs in).
    template <class Visit>
    void forEachFace(Visit visit) const {
        for (int c = 0; c < 3; ++c) {
            const glm::ivec3 n = faceCount(c);
            for (int k = 0; k < n.z; ++k)
                for (int j = 0; j < n.y; ++j)
                    for (int i = 0; i < n.x; ++i)
                        visit(c, glm::ivec3(i, j, k));
        }
    }
    glm::ivec3 cellCount() const { return cells_; }

private:
    Boundary boundary(int axis, bool high) const {
        return options_.boundaries[2 * axis + high].kind;
    }
    double dt() const { return double(options_.substepDt()); }

    // Pressure solvers (solve_pressure.cpp, red_black_gauss_seidel.cpp, multigrid.cpp,
    // mgpcg.cpp).
    void solvePressureJacobi();
    void solvePressureRedBlack();
    void solvePressureMultigrid();
    void solvePressureMgpcg();
    void recordResidual(); // appends pressureResidual() when recording

    // Advection schemes (semi_lagrangian.cpp, maccormack.cpp, bfecc.cpp). A field is a velocity
    // component 0..2 on its faces or kPigmentField, the RGBA pigment at cell centres.
    static constexpr int kPigmentField = 3;
    // `source` (laid out like `field`) advected by options().advection over the sub-step.
    Eigen::ArrayXd advectField(int field, const Eigen::ArrayXd& source) const;
    // Departure points of every sample point of `field`, traced over `interval`.
    std::vector<glm::dvec3> departurePoints(int field, double interval) const;
    // One semi-Lagrangian pass: each point takes `source` sampled at its departure point;
    // wall-normal faces are 0.
    Eigen::ArrayXd semiLagrangian(int field, const Eigen::ArrayXd& source,
                                  std::span<const glm::dvec3> departures) const;
    // The limiter: each value of `values` clamped to the range of the values of `source` that a
    // sample at its departure point interpolates from.
    void clampToSampleRange(int field, const Eigen::ArrayXd& source,
                            std::span<const glm::dvec3> departures, Eigen::ArrayXd& values) const;
    Eigen::ArrayXd advectMacCormack(int field, const Eigen::ArrayXd& source) const;
    Eigen::ArrayXd advectBfecc(int field, const Eigen::ArrayXd& source) const;

    // Storage::Float16 (half_storage.cpp): velocity, pressure and pigment rounded to half.
    void roundStoredFields();
    // The sparse domain: every value outside the active cells becomes 0 (sparse_domain.cpp).
    void clearInactive();
    // Solid faces of `velocity` set back to the solids' velocity (mark_solids.cpp).
    void keepSolidFaces(std::array<Eigen::ArrayXd, 3>& velocity) const;
    // Pressure neighbours of cell q as the Jacobi sweep counts them (solve_pressure.cpp): the sum
    // of the counted neighbours' pressure in `p` and their count.
    std::pair<double, int> countedNeighbours(const Eigen::ArrayXd& p, glm::ivec3 q) const;

    SolverOptions options_;
    double time_ = 0.0; // time()
    glm::ivec3 cells_;
    double h_;
    std::array<Eigen::ArrayXd, 3> velocity_;
    Eigen::ArrayXd pressure_;
    Eigen::ArrayXd divergence_;
    Eigen::ArrayXd pigment_;           // RGBA interleaved
    std::vector<uint8_t> activeCells_; // empty: dense
    std::vector<shared::FluidSolid> solids_;
    std::vector<uint8_t> solidCells_;             // per cell; empty without solids
    std::array<Eigen::ArrayXd, 3> solidVelocity_; // per face, read on solid faces only
    bool recordHistory_ = false;
    std::vector<double> residualHistory_;
    uint32_t pressureIterations_ = 0;
};

} // namespace mfx::fluid
