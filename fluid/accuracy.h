// Measures of a solver configuration's accuracy (motionfx bench accuracy; README "Accuracy
// against time"): runs of the CPU reference, optionally with the exact pressure solve as ground
// truth, a state on a grid twice as fine brought down to a coarser one to compare with, and how
// much divergence a projection leaves.
#pragma once

#include "fluid/scenarios.h"
#include "fluid/solver_options.h"

#include <cstdint>

namespace mfx::fluid {

// `steps` steps of `scenario` on the CPU reference with `options`; with `exact`, every pressure
// solve is the exact one (Eigen) instead of the configured solver.
FieldState referenceRun(const Scenario& scenario, const SolverOptions& options, uint32_t steps,
                        bool exact);

// A state on a grid twice as fine, restricted to `coarse`: pigment as the mean of the 8 fine
// cells of a coarse cell, a face velocity as the mean of the 4 fine faces on the coarse face.
FieldState restrictToCoarse(const FieldState& fine, const GridShape& coarse);

// ||div after projection|| / ||div before|| of a state whose divergence field holds the
// divergence the last pressure solve started from (0 when that was 0).
double divergenceLeft(const SolverOptions& options, const FieldState& state);

// A smooth, divergent velocity field on the options' grid (sines and cosines of the face
// positions, no symmetry) with its divergence computed by the reference (boundaries applied
// first): the input of bench accuracy's time-to-1e-3 measurement.
FieldState smoothDivergentState(const SolverOptions& options);

} // namespace mfx::fluid
