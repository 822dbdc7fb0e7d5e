// Solids with every pressure solver (docs/fluid.md, "Solids" and "Accuracy options"), on the CPU
// reference: red-black Gauss-Seidel, multigrid and MGPCG solve the equation the Jacobi sweep solves
// with solids (a solid cell has no unknown and holds p = 0, a side towards a solid cell is not
// counted), the multigrid hierarchy's coarse levels without the solids; a solid cell's pressure
// is 0 with each; a still sphere in a stream lets nothing through with each; a hierarchy of one
// level is refused.
#include "fluid/reference/reference_solver.h"
#include "tests/fluid_solids_util.h"
#include "tests/fluid_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace mfx::test {
namespace {

using fluid::PressureSolver;
using fluid::ReferenceSolver;

constexpr fluid::GridShape kGrid{16, 12, 10, 0.1f};

// A sphere and a capsule across the grid: together a tenth of its cells.
std::vector<shared::FluidSolid> solids() {
    return {solidSphere({0.55f, 0.6f, 0.5f}, 0.3f, {0.4f, 0.0f, -0.2f}),
            solidCapsule({0.9f, 0.2f, 0.3f}, {1.3f, 1.0f, 0.7f}, 0.15f, {0.0f, 0.5f, 0.0f},
                         {-0.3f, 0.2f, 0.1f})};
}

fluid::SolverOptions boxOptions(bool closed, PressureSolver solver) {
    fluid::SolverOptions o = closed ? closedBoxOptions(kGrid) : mixedBoundaryOptions(kGrid);
    o.pressureSolver = solver;
    o.warmStart = false;
    return o;
}

// The pressure a solver leaves for the solids' divergence from a random state (its pressure, the
// solid cells' pressure and the relative residual history), and the exact solution.
struct Solve {
    std::vector<double> pressure;
    std::vector<double> exact;
    std::vector<double> history;
    size_t solidCells = 0;
    double largestSolidPressure = 0.0;
};

Solve solveWithSolids(const fluid::SolverOptions& options) {
    ReferenceSolver s(options);
    s.setState(randomState(options.grid, 4242));
    s.setSolids(solids());
    s.computeDivergence();
    s.setRecordResidualHistory(true);
    ReferenceSolver exact = s;
    s.solvePressure();
    exact.solvePressureExact();
    Solve out;
    out.history = s.residualHistory();
    const fluid::FieldState state = s.state(), truth = exact.state();
    const fluid::GridShape& g = options.grid;
    // Without an open face p is defined up to a constant over the fluid cells: both mean-free.
    bool singular = true;
    for (const fluid::FaceBoundary& face : options.boundaries)
        singular = singular && face.kind != fluid::Boundary::Open;
    double mean = 0.0, exactMean = 0.0;
    size_t fluid = 0;
    for (uint32_t k = 0; k < g.cellsZ; ++k)
        for (uint32_t j = 0; j < g.cellsY; ++j)
            for (uint32_t i = 0; i < g.cellsX; ++i) {
                const size_t index = g.index(i, j, k);
                if (s.solidCell({int(i), int(j), int(k)})) {
                    ++out.solidCells;
                    out.largestSolidPressure =
                        std::max(out.largestSolidPressure, std::abs(double(state.pressure[index])));
                    continue;
                }
                mean += double(state.pressure[index]);
                exactMean += double(truth.pressure[index]);
                ++fluid;
                out.pressure.push_back(state.pressure[index]);
                out.exact.push_back(truth.pressure[index]);
            }
    if (singular && fluid > 0)
        for (size_t n = 0; n < out.pressure.size(); ++n) {
            out.pressure[n] -= mean / double(fluid);
            out.exact[n] -= exactMean / double(fluid);
        }
    return out;
}

// ||p - exact|| / ||exact|| over the fluid cells.
double relativeError(const Solve& s) {
    double difference = 0.0, norm = 0.0;
    for (size_t n = 0; n < s.pressure.size(); ++n) {
        difference += (s.pressure[n] - s.exact[n]) * (s.pressure[n] - s.exact[n]);
        norm += s.exact[n] * s.exact[n];
    }
    return std::sqrt(difference / norm);
}

const char* boundaryName(bool closed) {
    return closed ? "closed box" : "mixed faces";
}

TEST(FluidSolidsPressure, MgpcgConvergesToTheExactSolution) {
    for (bool closed : {true, false}) {
        fluid::SolverOptions o = boxOptions(closed, PressureSolver::MultigridPcg);
        o.cgTolerance = 1e-7f;
        o.cgMaxIterations = 100;
        const Solve s = solveWithSolids(o);
        ASSERT_GT(s.solidCells, 150u); // 192 of 1,920
        const double error = relativeError(s);
        std::printf("MGPCG, %s: %zu iterations to %.2e, %.2e from the exact pressure\n",
                    boundaryName(closed), s.history.size() - 1, s.history.back(), error);
        EXPECT_LE(s.history.back(), 1e-7) << boundaryName(closed);
        EXPECT_LE(error, 1e-5) << boundaryName(closed);
        EXPECT_EQ(s.largestSolidPressure, 0.0) << boundaryName(closed);
    }
}

TEST(FluidSolidsPressure, MultigridCyclesConvergeWithSolids) {
    for (bool closed : {true, false}) {
        fluid::SolverOptions o = boxOptions(closed, PressureSolver::Multigrid);
        o.multigrid.cycles = 12;
        const Solve s = solveWithSolids(o);
        std::printf("multigrid, %s: residual per cycle", boundaryName(closed));
        for (double r : s.history)
            std::printf(" %.2e", r);
        std::printf("; %.2e from the exact pressure\n", relativeError(s));
        // The mean reduction a cycle (without solids, the same grid: about 18x; the coarse levels
        // do not see the solids, which slows the cycles next to them).
        const double rate =
            std::pow(s.history.front() / s.history.back(), 1.0 / double(s.history.size() - 1));
        ReferenceSolver plain(o);
        plain.setState(randomState(o.grid, 4242));
        plain.computeDivergence();
        plain.setRecordResidualHistory(true);
        plain.solvePressure();
        const std::vector<double>& h = plain.residualHistory();
        const double plainRate = std::pow(h.front() / h.back(), 1.0 / double(h.size() - 1));
        std::printf("  %.2fx a cycle with the solids, %.2fx without\n", rate, plainRate);
        EXPECT_GE(rate, 3.0) << boundaryName(closed);
        EXPECT_LE(s.history.back(), 1e-4) << boundaryName(closed);
        EXPECT_LE(relativeError(s), 1e-3) << boundaryName(closed);
        EXPECT_EQ(s.largestSolidPressure, 0.0) << boundaryName(closed);
    }
}

TEST(FluidSolidsPressure, RedBlackConvergesFasterThanJacobiWithSolids) {
    for (bool closed : {true, false}) {
        fluid::SolverOptions o = boxOptions(closed, PressureSolver::RedBlackGaussSeidel);
        o.jacobiIterations = 60;
        const Solve redBlack = solveWithSolids(o);
        o.pressureSolver = PressureSolver::Jacobi;
        const Solve jacobi = solveWithSolids(o);
        std::printf("%s, 60 sweeps: red-black %.3e, Jacobi %.3e\n", boundaryName(closed),
                    redBlack.history.back(), jacobi.history.back());
        EXPECT_LT(redBlack.history.back(), 0.9 * jacobi.history.back()) << boundaryName(closed);
        EXPECT_LT(relativeError(redBlack), relativeError(jacobi)) << boundaryName(closed);
        EXPECT_EQ(redBlack.largestSolidPressure, 0.0) << boundaryName(closed);
    }
}

TEST(FluidSolidsPressure, AStillSphereInAStreamLetsNothingThroughWithEverySolver) {
    fluid::FieldState stream = fluid::FieldState::zero(kStreamGrid);
    for (float& u : stream.velocityX)
        u = 1.0f;
    const shared::FluidSolid ball = solidSphere({1.0f, 0.5f, 0.5f}, 0.2f);
    for (PressureSolver solver : {PressureSolver::RedBlackGaussSeidel, PressureSolver::Multigrid,
                                  PressureSolver::MultigridPcg}) {
        fluid::SolverOptions o = streamOptions();
        o.pressureSolver = solver;
        o.multigrid.cycles = 6; // about 3x a cycle with solids (MultigridCyclesConverge...)
        ReferenceSolver s(o);
        s.setState(stream);
        s.setSolids(std::span(&ball, 1));
        s.step({});
        EXPECT_EQ(solidFaceError(s, s.state(), glm::dvec3(0.0)), 0.0)
            << fluid::pressureSolverName(solver);
        std::printf("%s: relative residual after the step %.2e\n",
                    fluid::pressureSolverName(solver), s.pressureResidual());
        // Red-black sweeps are a smoother: the step's sweeps take it part of the way.
        const double bound = solver == PressureSolver::RedBlackGaussSeidel ? 0.1 : 1e-2;
        EXPECT_LT(s.pressureResidual(), bound) << fluid::pressureSolverName(solver);
    }
}

TEST(FluidSolidsPressure, AHierarchyOfOneLevelIsRefused) {
    for (PressureSolver solver : {PressureSolver::Multigrid, PressureSolver::MultigridPcg}) {
        fluid::SolverOptions o = boxOptions(true, solver);
        o.multigrid.levels = 1;
        ReferenceSolver s(o);
        const std::vector<shared::FluidSolid> both = solids();
        try {
            s.setSolids(both);
            ADD_FAILURE() << "accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_EQ(std::string(e.what()),
                      std::string("solids: the pressure solver \"") +
                          fluid::pressureSolverName(solver) +
                          "\" takes solids only with two multigrid levels or more");
        }
        o.multigrid.levels = 2;
        ReferenceSolver two(o);
        EXPECT_NO_THROW(two.setSolids(both));
    }
}

} // namespace
} // namespace mfx::test
