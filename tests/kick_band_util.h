// The fighter's roundhouse kick (its body capsules: fluid::bodySolids of anim::fitBodyCapsules)
// through a band of still smoke, for the reference (test_fluid_solids.cpp), the dense GPU solver
// (test_fluid_gpu_solids.cpp) and the sparse one (test_sparse_solids.cpp): 24³ cells of 8.3 cm
// round the fighter, open but for a free-slip floor, no emitter; the band's pigment 0.6 from
// y = 0.83 to 1.42 m. Measured: the largest share of the pigment in the body's solid cells after
// any step, and the band's mean fluid speed after the kick with and without the body.
#pragma once

#include "core/anim/body_capsules.h"
#include "core/anim/fighter.h"
#include "core/anim/sampling.h"
#include "fluid/body_solids.h"
#include "fluid/reference/reference_solver.h"
#include "tests/fluid_solids_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <vector>

namespace mfx::test {

inline constexpr uint32_t kKickBandCells = 24, kKickBandLow = 10, kKickBandHigh = 17;

inline fluid::SolverOptions kickBandOptions() {
    fluid::SolverOptions options;
    options.grid = {kKickBandCells, kKickBandCells, kKickBandCells, 2.0f / kKickBandCells};
    options.dt = 1.0f / 60.0f;
    options.jacobiIterations = 40;
    for (int face = 0; face < 6; ++face)
        options.boundaries[face].kind =
            face == fluid::FaceLowY ? fluid::Boundary::WallFreeSlip : fluid::Boundary::Open;
    return options;
}

inline fluid::FieldState kickBandCloud(const fluid::GridShape& g) {
    fluid::FieldState cloud = fluid::FieldState::zero(g);
    for (uint32_t k = 0; k < g.cellsZ; ++k)
        for (uint32_t j = kKickBandLow; j < kKickBandHigh; ++j)
            for (uint32_t i = 0; i < g.cellsX; ++i)
                for (size_t channel = 0; channel < 4; ++channel)
                    cloud.pigment[g.index(i, j, k) * 4 + channel] = 0.6f;
    return cloud;
}

struct KickBandRun {
    int steps = 0;
    double largestInside = 0.0; // of the pigment, in the body's solid cells, after any step
    double speed = 0.0;         // the band's mean fluid speed after the kick, with the body
    double stillSpeed = 0.0;    // and without it
};

// The kick from 0.2 to 0.7 s: `step(solids)` puts each step's body (where the step ends, in the
// grid's coordinates) into the solver that collides and steps both; `withState` and
// `withoutState` read their fields.
inline KickBandRun
runKickThroughBand(const fluid::SolverOptions& options,
                   const std::function<void(const std::vector<shared::FluidSolid>&)>& step,
                   const std::function<fluid::FieldState()>& withState,
                   const std::function<fluid::FieldState()>& withoutState) {
    const anim::Character fighter = anim::makeFighter();
    const anim::Clip* kick = fighter.findClip("roundhouse_kick");
    EXPECT_NE(kick, nullptr);
    const std::vector<anim::BodyCapsule> capsules = anim::fitBodyCapsules(fighter);
    const glm::vec3 origin(-1.0f, 0.0f, -1.0f);
    const fluid::GridShape& g = options.grid;
    fluid::ReferenceSolver marks(options); // the body's solid cells
    KickBandRun run;
    for (float t = 0.2f; t < 0.7f; t += options.dt, ++run.steps) {
        const std::vector<shared::FluidSolid> solids =
            fluid::bodySolids(capsules, anim::samplePose(fighter, kick, t),
                              anim::samplePose(fighter, kick, t + options.dt), options.dt, origin);
        marks.setSolids(solids);
        step(solids);
        const fluid::FieldState state = withState();
        double inside = 0.0, total = 0.0;
        for (int k = 0; k < int(g.cellsZ); ++k)
            for (int j = 0; j < int(g.cellsY); ++j)
                for (int i = 0; i < int(g.cellsX); ++i) {
                    const double alpha = state.pigment[g.index(i, j, k) * 4 + 3];
                    total += alpha;
                    if (marks.solidCell({i, j, k})) inside += alpha;
                }
        EXPECT_GT(total, 0.0);
        if (total > 0.0) run.largestInside = std::max(run.largestInside, inside / total);
    }
    run.speed = meanFluidSpeed(withState(), marks, int(kKickBandLow), int(kKickBandHigh));
    run.stillSpeed = meanFluidSpeed(withoutState(), marks, int(kKickBandLow), int(kKickBandHigh));
    return run;
}

} // namespace mfx::test
