// What the sparse grid's tests share (test_sparse_solver.cpp, test_sparse_solids.cpp): the
// domain's options, a solver, a chosen set of active bricks, and emitters.
#pragma once

#include "fluid/sparse_smoke_solver.h"
#include "tests/fluid_test_util.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace mfx::test::sparse_test {

using fluid::kBrickSize;
using fluid::SparseSmokeSolver;

// The scene's smoke: open on every side but a free-slip floor, RK2.
inline SolverOptions openOptions(GridShape grid = {24, 16, 16, 0.1f}) {
    SolverOptions o;
    o.grid = grid;
    o.dt = 0.05f;
    o.integrator = fluid::Integrator::RK2;
    o.fade = 0.5f;
    o.drag = 0.7f;
    o.buoyancy = 1.5f;
    o.jacobiIterations = 13;
    for (fluid::FaceBoundary& face : o.boundaries)
        face.kind = Boundary::Open;
    o.boundaries[fluid::FaceLowY].kind = Boundary::WallFreeSlip;
    return o;
}

// Walls of both kinds (a moving no-slip lid), an open side, Euler.
inline SolverOptions wallOptions(GridShape grid = {24, 16, 16, 0.1f}) {
    SolverOptions o;
    o.grid = grid;
    o.dt = 0.04f;
    o.buoyancy = 0.8f;
    o.fade = 0.2f;
    o.jacobiIterations = 20;
    o.warmStart = true;
    o.boundaries[fluid::FaceLowY].kind = Boundary::WallNoSlip;
    o.boundaries[fluid::FaceHighY].kind = Boundary::WallNoSlip;
    o.boundaries[fluid::FaceHighY].wallVelocity = {0.7f, 0.0f, -0.3f};
    o.boundaries[fluid::FaceLowZ].kind = Boundary::Open;
    return o;
}

inline std::unique_ptr<SparseSmokeSolver> makeSparse(const gpu::Context& ctx,
                                                     const SolverOptions& o,
                                                     uint32_t maxBricks = 4096,
                                                     uint32_t initialSlots = 64) {
    auto made = SparseSmokeSolver::create(ctx, o, maxBricks, initialSlots);
    EXPECT_TRUE(made.ok()) << (made.ok() ? "" : made.error().message);
    return made.ok() ? std::move(made).value() : nullptr;
}

// Wants the bricks for which `pick(brick)` holds, and commits.
template <typename Pick>
fluid::SparseBricks::Update activate(SparseSmokeSolver& s, Pick pick) {
    fluid::SparseBricks& layout = s.layout();
    layout.clearWanted();
    const glm::uvec3 n = layout.bricks();
    for (uint32_t z = 0; z < n.z; ++z)
        for (uint32_t y = 0; y < n.y; ++y)
            for (uint32_t x = 0; x < n.x; ++x)
                if (pick(glm::ivec3(x, y, z)))
                    layout.wantCell(glm::ivec3(x, y, z) * int(kBrickSize));
    return s.commitActive();
}

// About half the bricks of the domain, scattered (seeded), so that active bricks meet inactive
// ones across every kind of face, and at the domain's sides.
inline auto scattered(uint32_t seed) {
    return [seed](glm::ivec3 b) {
        const uint32_t h = (uint32_t(b.x) * 73856093u) ^ (uint32_t(b.y) * 19349663u) ^
                           (uint32_t(b.z) * 83492791u) ^ (seed * 2654435761u);
        return (h >> 7) % 2u == 0u;
    };
}

// Emitters in the domain of `o`, one reaching past its low x side.
inline std::vector<shared::FluidEmitter> emittersFor(const SolverOptions& o) {
    std::vector<shared::FluidEmitter> e = twoEmitters(o.grid);
    e.push_back(
        emitter({0.05f, 0.8f, 0.7f}, 0.4f, {2.0f, -0.5f, 0.3f}, 12.0f, {0.3f, 0.9f, 0.4f, 0.7f}));
    return e;
}

// A stage alone, with walls (wallOptions) or open (openOptions).
struct StageCase {
    fluid::Stage stage;
    bool walls;
};

inline std::string stageCaseName(const ::testing::TestParamInfo<StageCase>& info) {
    return std::string(fluid::stageName(info.param.stage)) +
           (info.param.walls ? "_walls" : "_open");
}

// Without solids, every stage the sparse domain runs (those with a sparse function in the stage
// table) but markSolids, which does nothing then; with solids, every stage of a sub-step it runs,
// markSolids included (applyBoundaries, which does not read them, runs only alone). Each with
// walls and open.
inline std::vector<StageCase> stageCases(bool solids) {
    std::vector<StageCase> cases;
    for (const fluid::StageEntry& entry : fluid::stageTable()) {
        if (!entry.sparse) continue;
        if (solids ? !entry.inStep : entry.stage == fluid::Stage::MarkSolids) continue;
        for (bool walls : {false, true})
            cases.push_back({entry.stage, walls});
    }
    return cases;
}

} // namespace mfx::test::sparse_test
