// solvePressure (docs/fluid.md): the Poisson equation of the projection, sum over the cell's
// counted neighbours of (p_n - p) = h² div, by the solver options().pressureSolver names: Jacobi
// here, red-black Gauss-Seidel, multigrid and MGPCG in files of their own. Jacobi sweeps are
//   p <- (sum of counted neighbour pressures - h² div) / count,
// where a neighbour across a wall is not counted (zero normal gradient), one across an open face is
// counted with p = 0, and a periodic one wraps. (The 7-point stencil divides by 6 in the interior;
// the source paper's eq. 17 prints 8.) solvePressureExact solves the same matrix with Eigen's
// conjugate gradient: the ground truth for how far N sweeps are from converged. pressureResidual
// measures any of them.
#include "fluid/reference/pressure_equation.h"
#include "fluid/reference/reference_solver.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <cmath>
#include <vector>

namespace mfx::fluid {

namespace {
const glm::ivec3 kSteps[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
}

void ReferenceSolver::solvePressure() {
    residualHistory_.clear();
    switch (options_.pressureSolver) {
    case PressureSolver::Jacobi:
        solvePressureJacobi();
        break;
    case PressureSolver::RedBlackGaussSeidel:
        solvePressureRedBlack();
        break;
    case PressureSolver::Multigrid:
        solvePressureMultigrid();
        break;
    case PressureSolver::MultigridPcg:
        solvePressureMgpcg();
        break;
    }
}

double ReferenceSolver::pressureResidual() const {
    // With solids, the equation over the fluid cells as the Jacobi sweep has it (PressureGrid:
    // solid neighbours not counted, solid rows 0; without an open face b mean-free over the
    // fluid cells).
    const PressureGrid grid = PressureGrid::finest(cells_, options_.boundaries, solidCells_);
    const Eigen::ArrayXd b = consistentRightHandSide(grid, -(h_ * h_) * divergence_);
    const double norm = b.matrix().norm();
    if (norm == 0.0) return 0.0;
    // A p sums to 0 when A is singular, so b - A p is mean-free as b is.
    return grid.residual(b, pressure_).matrix().norm() / norm;
}

void ReferenceSolver::recordResidual() {
    if (recordHistory_) residualHistory_.push_back(pressureResidual());
}

std::pair<double, int> ReferenceSolver::countedNeighbours(const Eigen::ArrayXd& p,
                                                          glm::ivec3 q) const {
    double sum = 0.0;
    int count = 0;
    for (int s = 0; s < 6; ++s) {
        const int axis = s / 2;
        glm::ivec3 neighbour = q + kSteps[s];
        if (neighbour[axis] >= 0 && neighbour[axis] < cells_[axis]) {
            if (solidCell(neighbour)) continue; // zero normal gradient, as at a wall
            sum += p[Eigen::Index(cellIndex(neighbour))];
            ++count;
        } else if (boundary(axis, s % 2 == 1) == Boundary::Periodic) {
            neighbour[axis] = (neighbour[axis] + cells_[axis]) % cells_[axis];
            if (solidCell(neighbour)) continue;
            sum += p[Eigen::Index(cellIndex(neighbour))];
            ++count;
        } else if (boundary(axis, s % 2 == 1) == Boundary::Open) {
            ++count; // ghost pressure 0
        }
    }
    return {sum, count};
}

void ReferenceSolver::solvePressureJacobi() {
    if (!options_.warmStart) pressure_.setZero();
    recordResidual();
    Eigen::ArrayXd next = pressure_;
    const double h2 = h_ * h_;
    for (uint32_t iteration = 0; iteration < options_.jacobiIterations; ++iteration) {
        for (int k = 0; k < cells_.z; ++k)
            for (int j = 0; j < cells_.y; ++j)
                for (int i = 0; i < cells_.x; ++i) {
                    const glm::ivec3 q(i, j, k);
                    if (!cellActive(q) || solidCell(q)) { // open air (sparse), or no unknown
                        next[Eigen::Index(cellIndex(q))] = 0.0;
                        continue;
                    }
                    const auto [sum, count] = countedNeighbours(pressure_, q);
                    const Eigen::Index index = Eigen::Index(cellIndex(q));
                    next[index] = count > 0 ? (sum - h2 * divergence_[index]) / count : 0.0;
                }
        std::swap(pressure_, next);
        recordResidual();
    }
    pressureIterations_ = options_.jacobiIterations;
}

void ReferenceSolver::solvePressureExact() {
    const Eigen::Index n = Eigen::Index(cells_.x) * cells_.y * cells_.z;
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(size_t(n) * 7);
    Eigen::VectorXd rhs(n);
    bool anyOpen = false;
    for (int k = 0; k < cells_.z; ++k)
        for (int j = 0; j < cells_.y; ++j)
            for (int i = 0; i < cells_.x; ++i) {
                const glm::ivec3 q(i, j, k);
                const Eigen::Index row = Eigen::Index(cellIndex(q));
                if (solidCell(q)) { // no unknown inside a solid: p = 0
                    entries.emplace_back(row, row, 1.0);
                    rhs[row] = 0.0;
                    continue;
                }
                double diagonal = 0.0;
                for (int s = 0; s < 6; ++s) {
                    const int axis = s / 2;
                    glm::ivec3 neighbour = q + kSteps[s];
                    const bool inside = neighbour[axis] >= 0 && neighbour[axis] < cells_[axis];
                    const Boundary b = boundary(axis, s % 2 == 1);
                    if (inside || b == Boundary::Periodic) {
                        neighbour[axis] = (neighbour[axis] + cells_[axis]) % cells_[axis];
                        if (solidCell(neighbour)) continue; // zero normal gradient
                        const Eigen::Index column = Eigen::Index(cellIndex(neighbour));
                        diagonal += 1.0;
                        entries.emplace_back(row, column, -1.0);
                    } else if (b == Boundary::Open) {
                        diagonal += 1.0;
                        anyOpen = true;
                    }
                }
                // An isolated cell (a 1x1x1 box of walls) has no equation: pin p = 0.
                entries.emplace_back(row, row, diagonal > 0.0 ? diagonal : 1.0);
                rhs[row] = diagonal > 0.0 ? -h_ * h_ * divergence_[row] : 0.0;
            }
    Eigen::SparseMatrix<double> matrix(n, n);
    matrix.setFromTriplets(entries.begin(), entries.end()); // duplicates (self-neighbours) sum
    // Without an open face the matrix is singular (constants are in its null space); the system
    // is consistent once the right-hand side has zero mean, which CG then solves.
    if (!anyOpen) {
        if (hasSolids()) { // mean-free over the fluid cells; the solid rows stay p = 0
            double sum = 0.0;
            Eigen::Index fluid = 0;
            for (Eigen::Index row = 0; row < n; ++row)
                if (solidCells_[size_t(row)] == 0) {
                    sum += rhs[row];
                    ++fluid;
                }
            for (Eigen::Index row = 0; row < n && fluid > 0; ++row)
                if (solidCells_[size_t(row)] == 0) rhs[row] -= sum / double(fluid);
        } else {
            rhs.array() -= rhs.mean();
        }
    }

    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
    cg.setTolerance(1e-12);
    cg.setMaxIterations(int(std::max<Eigen::Index>(10 * n, 1000)));
    cg.compute(matrix);
    Eigen::VectorXd guess = pressure_.matrix();
    const Eigen::VectorXd solution = cg.solveWithGuess(rhs, guess);
    pressure_ = solution.array();
}

} // namespace mfx::fluid
