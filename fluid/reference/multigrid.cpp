// Multigrid V-cycles on the pressure equation (docs/fluid.md, "Accuracy options"), after
// Trottenberg, Oosterlee, Schueller, "Multigrid" (2001), ch. 2 (the V-cycle, red-black
// Gauss-Seidel smoothing, cell-centred transfers) and McAdams, Sifakis, Teran, "A Parallel
// Multigrid Poisson Solver for Fluids Simulation on Large Grids" (SCA 2010): a cell-centred
// hierarchy whose V-cycle also serves as the preconditioner of MGPCG (mgpcg.cpp).
//
// - Hierarchy: every axis of at least 3 cells is halved, coarse cell I covering fine cells 2I and
//   2I+1; an odd count leaves one fine cell alone, at the end of the axis on even levels and at its
//   start on odd ones, so that the narrow cells do not pile up at one end. Axes of 1 or 2 cells
//   are kept. Each level has the same six boundary kinds and its own finite-volume operator
//   (pressure_equation.h): coefficient = side area / centre distance, rediscretised rather than
//   formed as P^T A P, so every level is a 7-point stencil that red-black smoothing decouples.
// - Prolongation P: trilinear interpolation of the coarse correction at each fine cell centre,
//   per axis between the two nearest coarse centres; beyond the last centre a wall repeats it
//   (zero gradient), an open face interpolates towards p = 0 at its ghost point, a periodic axis
//   wraps. Interpolation is of order 2, and meets with either restriction below the rule
//   m_P + m_R > 2 for a second-order operator given by Trottenberg et al.; piecewise-constant
//   transfers (order 1 + 1) do not, and their V-cycles slow down as the grid grows.
// - Restriction, two kinds. R0 (the multigrid solver): each coarse cell sums the residuals of the
//   fine cells it covers, the integral the finite-volume equations are written for. P^T (the MGPCG
//   preconditioner, which must be symmetric): each fine residual goes to the coarse cells with its
//   interpolation weights, which sum to 1 (less next to an open face). With 2 + 2 sweeps, R0 gives
//   8-14x per V-cycle at 32^3 and 64^3, P^T about 6x: the rediscretised coarse operator matches
//   the Galerkin operator P^T A P only for smooth errors, and R0's coarser averaging suits it
//   better.
// - Coarsest level: solved exactly by a sparse LDL^T factorisation. When no face is open the
//   operator is singular: the right-hand side is made mean-free, one cell pinned to 0 (the
//   remaining system is then nonsingular and, the right-hand side being consistent, its solution
//   satisfies the pinned equation too), and the solution made mean-free: the pseudo-inverse.
// - Smoothing: pre-smoothing red then black. Post-smoothing red then black for the solver; black
//   then red for the preconditioner, so that with equal counts the cycle is a symmetric operator
//   (the post-smoother is the adjoint of the pre-smoother), as conjugate gradient requires.
#include "fluid/reference/pressure_equation.h"
#include "fluid/reference/reference_solver.h"

#include <cmath>
#include <stdexcept>

namespace mfx::fluid {

namespace {

bool canHalve(int cells) {
    return cells >= 3;
}

} // namespace

std::vector<double> cellCentres(const std::vector<double>& widths) {
    std::vector<double> x(widths.size());
    double start = 0.0;
    for (size_t i = 0; i < widths.size(); ++i) {
        x[i] = start + 0.5 * widths[i];
        start += widths[i];
    }
    return x;
}

Multigrid::Multigrid(const PressureGrid& finest, uint32_t levels) {
    levels_.push_back(finest);
    for (;;) {
        const PressureGrid& fine = levels_.back();
        const glm::ivec3 n = fine.cells();
        if (!(canHalve(n.x) || canHalve(n.y) || canHalve(n.z))) break;
        if (levels != 0 && levels_.size() >= levels) break;
        const bool loneAtStart = levels_.size() % 2 == 0; // levels_.size() - 1 is odd
        std::array<std::vector<double>, 3> coarseWidths;
        std::array<std::vector<int>, 3> parent;
        for (int a = 0; a < 3; ++a) {
            const std::vector<double>& wf = fine.widths(a);
            parent[a].resize(wf.size());
            if (!canHalve(n[a])) {
                coarseWidths[a] = wf;
                for (size_t i = 0; i < wf.size(); ++i)
                    parent[a][i] = int(i);
                continue;
            }
            const bool shift = n[a] % 2 == 1 && loneAtStart;
            coarseWidths[a].assign(size_t((n[a] + 1) / 2), 0.0);
            for (int i = 0; i < n[a]; ++i) {
                const int I = shift ? (i + 1) / 2 : i / 2;
                parent[a][size_t(i)] = I;
                coarseWidths[a][size_t(I)] += wf[size_t(i)];
            }
        }
        PressureGrid coarse(coarseWidths, fine.boundaries());

        std::array<std::vector<Interpolation>, 3> interpolation;
        for (int a = 0; a < 3; ++a) {
            const std::vector<double> xf = cellCentres(fine.widths(a));
            const std::vector<double> xc = cellCentres(coarseWidths[a]);
            const std::vector<double>& wc = coarseWidths[a];
            const int nc = int(wc.size());
            interpolation[a].resize(xf.size());
            for (size_t i = 0; i < xf.size(); ++i) {
                Interpolation& in = interpolation[a][i];
                const int I = parent[a][i];
                in.coarse[0] = I;
                in.weight[0] = 1.0;
                const double offset = xf[i] - xc[size_t(I)];
                if (offset == 0.0) continue; // centres are half-integers: exact
                const int high = offset > 0.0 ? 1 : 0;
                const int J = high ? I + 1 : I - 1;
                int other = -1;
                double distance = 0.0;
                if (J >= 0 && J < nc) {
                    other = J;
                    distance = std::abs(xc[size_t(J)] - xc[size_t(I)]);
                } else {
                    switch (fine.boundaries()[size_t(2 * a + high)]) {
                    case Boundary::Periodic:
                        other = high ? 0 : nc - 1;
                        distance = 0.5 * (wc[size_t(I)] + wc[size_t(other)]);
                        break;
                    case Boundary::Open: // towards the ghost's p = 0, half a finest cell out
                        distance = 0.5 * (wc[size_t(I)] + 1.0);
                        break;
                    case Boundary::WallFreeSlip:
                    case Boundary::WallNoSlip:
                        continue; // zero gradient: the coarse value itself
                    }
                }
                const double t = std::abs(offset) / distance;
                in.weight[0] = 1.0 - t;
                in.coarse[1] = other;
                in.weight[1] = other >= 0 ? t : 0.0;
            }
        }
        interpolation_.push_back(std::move(interpolation));
        parent_.push_back(std::move(parent));
        levels_.push_back(std::move(coarse));
    }

    const PressureGrid& coarsest = levels_.back();
    if (coarsest.hasSolids())
        throw std::invalid_argument("multigrid: solids need a coarse level (levels >= 2 and an "
                                    "axis of 3 cells or more)");
    Eigen::SparseMatrix<double> matrix = coarsest.matrix();
    if (coarsest.singular()) {
        matrix.prune([](const Eigen::Index& row, const Eigen::Index& col, const double&) {
            return row != 0 && col != 0;
        });
        matrix.coeffRef(0, 0) = 1.0;
    }
    coarsest_ = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(matrix);
}

Multigrid::~Multigrid() = default;

namespace {

// Calls visit(fine, coarse, weight) for each fine cell of `fineGrid` (in index order) and each
// coarse cell of `coarseGrid` its trilinear interpolation `in` reads (open ghosts left out): the
// entries of P, row by row.
template <class Visit>
void forEachProlongationWeight(const PressureGrid& fineGrid, const PressureGrid& coarseGrid,
                               const std::array<std::vector<Multigrid::Interpolation>, 3>& in,
                               Visit&& visit) {
    const glm::ivec3 n = fineGrid.cells();
    for (int k = 0; k < n.z; ++k)
        for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i) {
                const Multigrid::Interpolation& x = in[0][size_t(i)];
                const Multigrid::Interpolation& y = in[1][size_t(j)];
                const Multigrid::Interpolation& z = in[2][size_t(k)];
                const Eigen::Index fine = Eigen::Index(fineGrid.index({i, j, k}));
                for (int c = 0; c < 2; ++c)
                    for (int b = 0; b < 2; ++b)
                        for (int a = 0; a < 2; ++a) {
                            if (x.coarse[a] < 0 || y.coarse[b] < 0 || z.coarse[c] < 0) continue;
                            const glm::ivec3 Q(x.coarse[a], y.coarse[b], z.coarse[c]);
                            visit(fine, Eigen::Index(coarseGrid.index(Q)),
                                  x.weight[a] * y.weight[b] * z.weight[c]);
                        }
            }
}

} // namespace

Eigen::ArrayXd Multigrid::prolong(size_t l, const Eigen::ArrayXd& coarse) const {
    Eigen::ArrayXd fine = Eigen::ArrayXd::Zero(levels_[l].size());
    forEachProlongationWeight(
        levels_[l], levels_[l + 1], interpolation_[l],
        [&](Eigen::Index f, Eigen::Index c, double w) { fine[f] += w * coarse[c]; });
    return fine;
}

Eigen::ArrayXd Multigrid::restrictTranspose(size_t l, const Eigen::ArrayXd& fine) const {
    Eigen::ArrayXd coarse = Eigen::ArrayXd::Zero(levels_[l + 1].size());
    forEachProlongationWeight(
        levels_[l], levels_[l + 1], interpolation_[l],
        [&](Eigen::Index f, Eigen::Index c, double w) { coarse[c] += w * fine[f]; });
    return coarse;
}

Eigen::ArrayXd Multigrid::restrictSum(size_t l, const Eigen::ArrayXd& fine) const {
    const PressureGrid& fineGrid = levels_[l];
    const PressureGrid& coarseGrid = levels_[l + 1];
    const auto& parent = parent_[l];
    Eigen::ArrayXd coarse = Eigen::ArrayXd::Zero(coarseGrid.size());
    const glm::ivec3 n = fineGrid.cells();
    for (int k = 0; k < n.z; ++k)
        for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i) {
                const glm::ivec3 Q(parent[0][size_t(i)], parent[1][size_t(j)],
                                   parent[2][size_t(k)]);
                coarse[Eigen::Index(coarseGrid.index(Q))] +=
                    fine[Eigen::Index(fineGrid.index({i, j, k}))];
            }
    return coarse;
}

Eigen::ArrayXd Multigrid::solveCoarsest(const Eigen::ArrayXd& b) const {
    const PressureGrid& grid = levels_.back();
    Eigen::VectorXd rhs = consistentRightHandSide(grid, b).matrix();
    if (grid.singular()) rhs[0] = 0.0; // the pinned cell
    Eigen::ArrayXd x = coarsest_->solve(rhs).array();
    if (grid.singular()) x -= x.mean();
    return x;
}

void Multigrid::cycle(size_t l, Eigen::ArrayXd& x, const Eigen::ArrayXd& b, uint32_t preSmooth,
                      uint32_t postSmooth, Cycle kind) const {
    if (l + 1 == levels_.size()) {
        x = solveCoarsest(b);
        return;
    }
    const PressureGrid& grid = levels_[l];
    grid.redBlackSweeps(x, b, preSmooth, false);
    const Eigen::ArrayXd residual = grid.residual(b, x);
    const Eigen::ArrayXd coarseB =
        kind == Cycle::Symmetric ? restrictTranspose(l, residual) : restrictSum(l, residual);
    Eigen::ArrayXd coarseX = Eigen::ArrayXd::Zero(coarseB.size());
    cycle(l + 1, coarseX, coarseB, preSmooth, postSmooth, kind);
    x += grid.withoutSolids(prolong(l, coarseX)); // no unknown in a solid cell
    grid.redBlackSweeps(x, b, postSmooth, kind == Cycle::Symmetric);
}

void Multigrid::vCycle(Eigen::ArrayXd& x, const Eigen::ArrayXd& b, uint32_t preSmooth,
                       uint32_t postSmooth, Cycle kind) const {
    cycle(0, x, b, preSmooth, postSmooth, kind);
}

// multigrid.cycles V-cycles from 0 (cold) or the last pressure (warm start), on the mean-free
// right-hand side when no face is open.
void ReferenceSolver::solvePressureMultigrid() {
    if (!options_.warmStart) pressure_.setZero();
    const PressureGrid grid = PressureGrid::finest(cells_, options_.boundaries, solidCells_);
    pressure_ = grid.withoutSolids(std::move(pressure_));
    const Eigen::ArrayXd b = consistentRightHandSide(grid, -(h_ * h_) * divergence_);
    const Multigrid multigrid(grid, options_.multigrid.levels);
    recordResidual();
    for (uint32_t cycle = 0; cycle < options_.multigrid.cycles; ++cycle) {
        multigrid.vCycle(pressure_, b, options_.multigrid.preSmooth, options_.multigrid.postSmooth,
                         Multigrid::Cycle::Standard);
        recordResidual();
    }
    pressureIterations_ = options_.multigrid.cycles;
}

} // namespace mfx::fluid
