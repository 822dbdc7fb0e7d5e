// MGPCG: conjugate gradient on the pressure equation preconditioned by one multigrid V-cycle per
// iteration (docs/fluid.md, "Accuracy options"), after McAdams, Sifakis, Teran, "A Parallel
// Multigrid Poisson Solver for Fluids Simulation on Large Grids" (SCA 2010), with the
// preconditioned conjugate gradient iteration of Saad, "Iterative Methods for Sparse Linear
// Systems" (2nd ed., 2003), algorithm 9.1:
//   r0 = b - A x0, z0 = M r0, d0 = z0;
//   alpha = (r, z) / (d, A d); x += alpha d; r -= alpha A d;
//   z = M r; beta = (r, z)_new / (r, z)_old; d = z + beta d.
// M is one V-cycle from zero (multigrid.cpp) with s = max(preSmooth, postSmooth, 1) red-black
// sweeps before and s black-red sweeps after: a symmetric operator, as CG requires (postSmooth is
// not used on its own: unequal counts would make M unsymmetric). Without an open face A is
// singular: b is made mean-free, and so is every z, so the iterates stay in the range of A.
// Stops when ||r|| <= cgTolerance ||b|| (r is CG's updated residual) or after cgMaxIterations.
#include "fluid/reference/pressure_equation.h"
#include "fluid/reference/reference_solver.h"

#include <algorithm>

namespace mfx::fluid {

void ReferenceSolver::solvePressureMgpcg() {
    if (!options_.warmStart) pressure_.setZero();
    pressureIterations_ = 0;
    const PressureGrid grid = PressureGrid::finest(cells_, options_.boundaries, solidCells_);
    pressure_ = grid.withoutSolids(std::move(pressure_));
    const Eigen::ArrayXd b = consistentRightHandSide(grid, -(h_ * h_) * divergence_);
    const double bNorm = b.matrix().norm();
    if (bNorm == 0.0) {
        pressure_.setZero(); // A p = 0: p = 0 (up to a constant when singular)
        if (recordHistory_) residualHistory_.push_back(0.0);
        return;
    }
    const Multigrid multigrid(grid, options_.multigrid.levels);
    const uint32_t smooth =
        std::max({options_.multigrid.preSmooth, options_.multigrid.postSmooth, 1u});
    auto precondition = [&](const Eigen::ArrayXd& r) {
        Eigen::ArrayXd z = Eigen::ArrayXd::Zero(r.size());
        multigrid.vCycle(z, r, smooth, smooth, Multigrid::Cycle::Symmetric);
        return consistentRightHandSide(grid, std::move(z));
    };
    auto dot = [](const Eigen::ArrayXd& a, const Eigen::ArrayXd& c) { return (a * c).sum(); };

    Eigen::ArrayXd r = consistentRightHandSide(grid, grid.residual(b, pressure_));
    double relative = r.matrix().norm() / bNorm;
    if (recordHistory_) residualHistory_.push_back(relative);
    const double tolerance = double(options_.cgTolerance);
    if (relative <= tolerance) return;
    Eigen::ArrayXd z = precondition(r);
    Eigen::ArrayXd d = z;
    double rz = dot(r, z);
    while (pressureIterations_ < options_.cgMaxIterations) {
        const Eigen::ArrayXd q = grid.apply(d);
        const double dq = dot(d, q);
        if (!(dq > 0.0)) break; // d = 0: r = 0 already
        const double alpha = rz / dq;
        pressure_ += alpha * d;
        r -= alpha * q;
        ++pressureIterations_;
        relative = r.matrix().norm() / bNorm;
        if (recordHistory_) residualHistory_.push_back(relative);
        if (relative <= tolerance) break;
        z = precondition(r);
        const double rzNext = dot(r, z);
        d = z + (rzNext / rz) * d;
        rz = rzNext;
    }
}

} // namespace mfx::fluid
