#include "fluid/stage_table.h"

#include "fluid/reference/reference_solver.h"
#include "fluid/smoke_solver.h"
#include "fluid/solver_options.h"
#include "fluid/sparse_smoke_solver.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace mfx::fluid {

namespace {

// --- Bytes models ---------------------------------------------------------------------------
// In values of the options' storage (4 bytes, or 2 for fp16); F3 = the faces of all three velocity
// components, N = the cells. Pigment is four values a cell.

struct Counts {
    double value;                // bytes of one stored value
    double cells;                // N
    std::array<double, 3> faces; // faces of each component
    double faces3() const { return faces[0] + faces[1] + faces[2]; }
};

Counts countsOf(const SolverOptions& o) {
    Counts c;
    c.value = o.storage == Storage::Float16 ? 2.0 : 4.0;
    c.cells = double(o.grid.cellCount());
    for (int axis = 0; axis < 3; ++axis) {
        const glm::uvec3 n = faceExtent(o.grid, axis);
        c.faces[size_t(axis)] = double(n.x) * double(n.y) * double(n.z);
    }
    return c;
}

StageBytes values(const Counts& c, double read, double written) {
    return {read * c.value, written * c.value};
}

// Passes of the advection scheme: semi-Lagrangian 1, MacCormack 2, BFECC 3.
double advectionPasses(const SolverOptions& o) {
    switch (o.advection) {
    case AdvectionScheme::SemiLagrangian:
        break;
    case AdvectionScheme::MacCormack:
        return 2.0;
    case AdvectionScheme::Bfecc:
        return 3.0;
    }
    return 1.0;
}

StageBytes markSolidsBytes(const SolverOptions& o, const StageWork& w) {
    // Whatever the storage: the holder (a 32-bit word a cell) cleared and read once by the flags'
    // pass, the flags (a byte a cell) written once (the few solid faces and cells, and the boxes
    // the solids mark, not counted: a small part of the grid).
    if (w.solids == 0) return {};
    const double cells = double(o.grid.cellCount());
    return {4.0 * cells, 5.0 * cells};
}

StageBytes splatBytes(const SolverOptions& o, const StageWork& w) {
    // Velocity (three faces a cell, near enough) and pigment of the emitters' boxes, read and
    // written.
    const Counts c = countsOf(o);
    const double box = double(w.splatCells);
    return values(c, 7.0 * box, 7.0 * box);
}

StageBytes advectVelocityBytes(const SolverOptions& o, const StageWork&) {
    // The first pass reads the velocity once (it both traces and is sampled) and writes it; each
    // further pass also reads the previous pass's result.
    const Counts c = countsOf(o);
    const double passes = advectionPasses(o);
    return values(c, c.faces3() * (2.0 * passes - 1.0), c.faces3() * passes);
}

StageBytes advectPigmentBytes(const SolverOptions& o, const StageWork&) {
    const Counts c = countsOf(o);
    const double passes = advectionPasses(o);
    return values(c, passes * c.faces3() + 4.0 * c.cells * (2.0 * passes - 1.0),
                  4.0 * c.cells * passes);
}

StageBytes buoyancyBytes(const SolverOptions& o, const StageWork&) {
    if (o.buoyancy == 0.0f) return {};
    const Counts c = countsOf(o);
    return values(c, c.faces[1] + 4.0 * c.cells, c.faces[1]);
}

StageBytes vorticityBytes(const SolverOptions& o, const StageWork&) {
    if (o.vorticity == 0.0f) return {};
    // The curl, the confinement force and its application need nothing but the velocity.
    const Counts c = countsOf(o);
    return values(c, c.faces3(), c.faces3());
}

StageBytes turbulenceBytes(const SolverOptions& o, const StageWork&) {
    if (o.turbulence == 0.0f) return {};
    // The noise is computed, not read: the velocity read and written once.
    const Counts c = countsOf(o);
    return values(c, c.faces3(), c.faces3());
}

StageBytes viscosityBytes(const SolverOptions& o, const StageWork&) {
    if (o.viscosity == 0.0f || o.viscosityIterations == 0) return {};
    // Each Jacobi sweep reads the previous iterate and the step's starting velocity.
    const Counts c = countsOf(o);
    const double sweeps = double(o.viscosityIterations);
    return values(c, 2.0 * c.faces3() * sweeps, c.faces3() * sweeps);
}

StageBytes boundariesBytes(const SolverOptions& o, const StageWork&) {
    // The two layers of faces normal to each axis.
    const Counts c = countsOf(o);
    double faces = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
        const glm::uvec3 n = faceExtent(o.grid, axis);
        faces += 2.0 * c.faces[size_t(axis)] / double(n[axis]);
    }
    return values(c, faces, faces);
}

StageBytes divergenceBytes(const SolverOptions& o, const StageWork&) {
    // With the Jacobi solve's first sweep in it, it also writes that sweep's pressure.
    const Counts c = countsOf(o);
    return values(c, c.faces3(), c.cells * (o.firstSweepFused() ? 2.0 : 1.0));
}

// One V-cycle from the finest level down: per level of N cells, each smoothing sweep reads x and
// the right-hand side and writes x; the prolongation reads the coarse x and x and writes x. The
// multigrid solver's restriction (R0) need not write the residual: it can compute it as it goes
// (MultigridOptions::residualInRestriction), reading x and the right-hand side and writing an
// eighth; where it does not (a CPU device) it moves 3 N more than this. MGPCG's (P^T) reads the
// residual another pass wrote (that pass: x and the right-hand side read, r written) and writes
// an eighth.
double vCycleValues(const SolverOptions& o) {
    const MultigridOptions& m = o.multigrid;
    const bool residualPass = o.pressureSolver == PressureSolver::MultigridPcg;
    glm::uvec3 n(o.grid.cellsX, o.grid.cellsY, o.grid.cellsZ);
    double total = 0.0;
    for (uint32_t level = 0; m.levels == 0 || level < m.levels; ++level) {
        const double cells = double(n.x) * double(n.y) * double(n.z);
        const double restriction = residualPass ? 3.0 * cells + 1.125 * cells : 2.125 * cells;
        total += 3.0 * cells * double(m.preSmooth + m.postSmooth) + restriction + 2.125 * cells;
        if (m.levels == 0 && (n.x < 4 || n.y < 4 || n.z < 4)) break;
        n = glm::max(n / 2u, glm::uvec3(1));
    }
    return total;
}

StageBytes pressureBytes(const SolverOptions& o, const StageWork& w) {
    const Counts c = countsOf(o);
    const double n = c.cells;
    const double sweeps = double(o.jacobiIterations);
    switch (o.pressureSolver) {
    case PressureSolver::Jacobi:
        // Each sweep reads pressure and divergence and writes pressure; a cold start's first
        // sweep reads no pressure (it is 0), and with no sweep the pressure is cleared. In a step
        // the divergence pass may do that first sweep (SolverOptions::firstSweepInDivergence).
        if (o.warmStart) return values(c, 2.0 * n * sweeps, n * sweeps);
        if (sweeps == 0.0) return values(c, 0.0, n);
        if (o.firstSweepFused()) return values(c, 2.0 * n * (sweeps - 1.0), n * (sweeps - 1.0));
        return values(c, 2.0 * n * sweeps - n, n * sweeps);
    case PressureSolver::RedBlackGaussSeidel:
        // Each sweep reads pressure and divergence and writes pressure; a cold start clears it.
        return values(c, 2.0 * n * sweeps, n * sweeps + (o.warmStart ? 0.0 : n));
    case PressureSolver::Multigrid:
        return values(c, 0.6 * vCycleValues(o) * double(o.multigrid.cycles) + n,
                      0.4 * vCycleValues(o) * double(o.multigrid.cycles) + n);
    case PressureSolver::MultigridPcg: {
        // The iterations it ran (at most cgMaxIterations): one V-cycle each, the operator (2N),
        // the two dot products (4N) and the three vector updates (9N).
        const double iteration = vCycleValues(o) + 15.0 * n;
        const uint32_t iterations = w.pressureIterations > 0
                                        ? std::min(w.pressureIterations, o.cgMaxIterations)
                                        : o.cgMaxIterations;
        const double all = iteration * double(iterations) + 2.0 * n;
        return values(c, 0.6 * all, 0.4 * all);
    }
    }
    return {};
}

StageBytes projectBytes(const SolverOptions& o, const StageWork&) {
    const Counts c = countsOf(o);
    return values(c, c.faces3() + c.cells, c.faces3());
}

// --- The table ----------------------------------------------------------------------------------

template <void (ReferenceSolver::*Member)()>
void referenceStage(ReferenceSolver& solver, Emitters) {
    (solver.*Member)();
}

void referenceSplat(ReferenceSolver& solver, Emitters emitters) {
    solver.splatImpulses(emitters);
}

} // namespace

// A friend of the three solvers: the table names their private stage functions.
std::span<const StageEntry> stageTable() {
    static const StageEntry table[] = {
        {Stage::MarkSolids, "mark_solids", "mark_solids", "sparse_mark_solids",
         &SmokeSolver::markSolids, &SparseSmokeSolver::markSolids,
         referenceStage<&ReferenceSolver::markSolids>, markSolidsBytes,
         "each cell's holder (a word) cleared and read once, its flag byte written", true},
        {Stage::SplatImpulses, "splat_impulses", "emitter_bounds splat_impulses",
         "sparse_splat_impulses", &SmokeSolver::splatImpulses, &SparseSmokeSolver::splatImpulses,
         referenceSplat, splatBytes,
         "velocity (3 faces a cell) and pigment (4) of the emitters' boxes, read and written",
         true},
        {Stage::AdvectVelocity, "advect_velocity", "advect_velocity", "sparse_advect_velocity",
         &SmokeSolver::advectVelocity, &SparseSmokeSolver::advectVelocity,
         referenceStage<&ReferenceSolver::advectVelocity>, advectVelocityBytes,
         "velocity read (2P-1) times and written P times, P the scheme's passes", true},
        {Stage::AdvectPigment, "advect_pigment", "advect_pigment", "sparse_advect_pigment",
         &SmokeSolver::advectPigment, &SparseSmokeSolver::advectPigment,
         referenceStage<&ReferenceSolver::advectPigment>, advectPigmentBytes,
         "per pass velocity read; pigment (4) read (2P-1) times, written P times", true},
        {Stage::ApplyBuoyancy, "apply_buoyancy", "apply_buoyancy", "sparse_apply_buoyancy",
         &SmokeSolver::applyBuoyancy, &SparseSmokeSolver::applyBuoyancy,
         referenceStage<&ReferenceSolver::applyBuoyancy>, buoyancyBytes,
         "y faces and pigment (4) read, y faces written", true},
        {Stage::VorticityConfinement, "vorticity_confinement",
         "compute_vorticity confinement_force apply_vorticity_force vorticity_force", "",
         &SmokeSolver::vorticityConfinement, nullptr,
         referenceStage<&ReferenceSolver::vorticityConfinement>, vorticityBytes,
         "velocity read and written once (curl and force need nothing else)", true},
        {Stage::ApplyTurbulence, "apply_turbulence", "turbulence_potential apply_turbulence", "",
         &SmokeSolver::applyTurbulence, nullptr, referenceStage<&ReferenceSolver::applyTurbulence>,
         turbulenceBytes, "velocity read and written once (the curl noise is computed)", true},
        {Stage::DiffuseViscosity, "diffuse_viscosity", "diffuse_viscosity", "",
         &SmokeSolver::diffuseViscosity, nullptr,
         referenceStage<&ReferenceSolver::diffuseViscosity>, viscosityBytes,
         "per sweep: velocity and the starting velocity read, velocity written", true},
        {Stage::ApplyBoundaries, "apply_boundaries", "apply_boundaries", "sparse_apply_boundaries",
         &SmokeSolver::applyBoundaries, &SparseSmokeSolver::applyBoundaries,
         referenceStage<&ReferenceSolver::applyBoundaries>, boundariesBytes,
         "the two boundary layers of faces of each axis, read and written", false},
        {Stage::ComputeDivergence, "compute_divergence", "compute_divergence",
         "sparse_compute_divergence", &SmokeSolver::computeDivergence,
         &SparseSmokeSolver::computeDivergence, referenceStage<&ReferenceSolver::computeDivergence>,
         divergenceBytes,
         "velocity read, divergence written (a cold Jacobi solve: and its first sweep's pressure)",
         true},
        {Stage::SolvePressure, "solve_pressure", "solve_pressure", "sparse_solve_pressure",
         &SmokeSolver::solvePressure, &SparseSmokeSolver::solvePressure,
         referenceStage<&ReferenceSolver::solvePressure>, pressureBytes,
         "per sweep: pressure and divergence read, pressure written (a cold Jacobi solve: the "
         "first sweep in the divergence; multigrid: per level)",
         true},
        {Stage::Project, "project", "project", "sparse_project", &SmokeSolver::project,
         &SparseSmokeSolver::project, referenceStage<&ReferenceSolver::project>, projectBytes,
         "velocity and pressure read, velocity written", true},
    };
    static_assert(std::size(table) == kStageCount, "one entry per stage");
    return table;
}

// The table lists the stages in the enum's order (tests/test_stage_table.cpp checks it).
const StageEntry& stageEntry(Stage stage) {
    const size_t index = size_t(stage);
    if (index >= kStageCount) throw std::logic_error("no stage " + std::to_string(index));
    return stageTable()[index];
}

const std::vector<Stage>& allStages() {
    static const std::vector<Stage> stages = [] {
        std::vector<Stage> list;
        for (const StageEntry& entry : stageTable())
            list.push_back(entry.stage);
        return list;
    }();
    return stages;
}

const std::vector<Stage>& stepOrder() {
    static const std::vector<Stage> order = [] {
        std::vector<Stage> list;
        for (const StageEntry& entry : stageTable())
            if (entry.inStep) list.push_back(entry.stage);
        return list;
    }();
    return order;
}

const char* stageName(Stage stage) {
    const size_t index = size_t(stage);
    return index < kStageCount ? stageTable()[index].name : "?";
}

std::optional<Stage> stageFromName(std::string_view name) {
    for (const StageEntry& entry : stageTable())
        if (name == entry.name) return entry.stage;
    return std::nullopt;
}

StageBytes stepBytes(const SolverOptions& options, const StageWork& work) {
    StageBytes total;
    for (Stage stage : stepOrder()) {
        const StageBytes b = stageEntry(stage).bytes(options, work);
        total.read += b.read;
        total.written += b.written;
    }
    return total;
}

} // namespace mfx::fluid
