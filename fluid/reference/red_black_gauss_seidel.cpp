// Red-black Gauss-Seidel on the pressure equation (docs/fluid.md, "Accuracy options"), after
// Trottenberg, Oosterlee, Schueller, "Multigrid" (2001), ch. 2 (GS-RB smoothing): the cells are
// coloured by the parity of i + j + k, and one sweep updates every red cell, then every black one,
//   p_q <- (sum_s c_s p_n(s) + b_q) / sum_s c_s,
// the Jacobi formula of docs/fluid.md step 10 (c_s = 1 on the simulation grid). A 7-point stencil
// couples only cells of different colours, so a colour's updates are independent: each reads the
// values as they stood before its half-sweep, which is Gauss-Seidel in place whenever the colours
// decouple and stays well defined (and parallel) when they do not: an odd periodic axis wraps a
// cell onto one of its own colour.
#include "fluid/reference/pressure_equation.h"
#include "fluid/reference/reference_solver.h"

namespace mfx::fluid {

void PressureGrid::relaxColour(Eigen::ArrayXd& p, const Eigen::ArrayXd& b, int colour) const {
    Eigen::ArrayXd next = p;
    for (int k = 0; k < cells_.z; ++k)
        for (int j = 0; j < cells_.y; ++j)
            for (int i = (colour + j + k) % 2; i < cells_.x; i += 2) {
                const glm::ivec3 q(i, j, k);
                const Eigen::Index cell = Eigen::Index(index(q));
                double weighted = 0.0, total = 0.0;
                neighbourSums(p, q, weighted, total);
                next[cell] = total > 0.0 ? (weighted + b[cell]) / total : 0.0;
            }
    p = std::move(next);
}

void PressureGrid::redBlackSweeps(Eigen::ArrayXd& p, const Eigen::ArrayXd& b, uint32_t sweeps,
                                  bool blackFirst) const {
    const int first = blackFirst ? 1 : 0;
    for (uint32_t sweep = 0; sweep < sweeps; ++sweep) {
        relaxColour(p, b, first);
        relaxColour(p, b, 1 - first);
    }
}

// jacobiIterations sweeps from 0 (cold) or the last pressure (warm start), on b = -h² div as the
// Jacobi sweep takes it (not made mean-free: like Jacobi, a pure smoother).
void ReferenceSolver::solvePressureRedBlack() {
    if (!options_.warmStart) pressure_.setZero();
    const PressureGrid grid = PressureGrid::finest(cells_, options_.boundaries, solidCells_);
    pressure_ = grid.withoutSolids(std::move(pressure_));
    const Eigen::ArrayXd b = grid.withoutSolids(-(h_ * h_) * divergence_);
    recordResidual();
    for (uint32_t sweep = 0; sweep < options_.jacobiIterations; ++sweep) {
        grid.redBlackSweeps(pressure_, b, 1);
        recordResidual();
    }
    pressureIterations_ = options_.jacobiIterations;
}

} // namespace mfx::fluid
