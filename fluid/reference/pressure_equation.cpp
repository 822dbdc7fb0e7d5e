// The pressure equation on a grid of cells of possibly unequal widths (pressure_equation.h): the
// finite-volume operator A with its boundary rules, its residual and its sparse matrix. On the
// simulation grid this is exactly the system of docs/fluid.md, step 10 (Bridson 2015, ch. 5); on a
// multigrid level it is the same finite-volume rule on the larger cells (Trottenberg et al. 2001,
// ch. 2: rediscretisation of the coarse-grid operator).
#include "fluid/reference/pressure_equation.h"

#include <stdexcept>
#include <vector>

namespace mfx::fluid {

PressureGrid::PressureGrid(std::array<std::vector<double>, 3> widths,
                           std::array<Boundary, 6> boundaries)
    : widths_(std::move(widths)), boundaries_(boundaries) {
    for (int a = 0; a < 3; ++a)
        cells_[a] = int(widths_[a].size());
    stride_ = {1, cells_.x, cells_.x * cells_.y};
    for (Boundary b : boundaries_)
        if (b == Boundary::Open) singular_ = false;
    for (int a = 0; a < 3; ++a) {
        const int n = cells_[a];
        const std::vector<double>& w = widths_[a];
        for (int high = 0; high < 2; ++high) {
            std::vector<Side>& sides = sides_[a][size_t(high)];
            sides.resize(size_t(n));
            for (int i = 0; i < n; ++i) {
                Side& side = sides[size_t(i)];
                const int inside = high ? i + 1 : i - 1;
                if (inside >= 0 && inside < n) {
                    side.neighbour = inside;
                    side.inverseDistance = 2.0 / (w[size_t(i)] + w[size_t(inside)]);
                    continue;
                }
                switch (boundaries_[size_t(2 * a + high)]) {
                case Boundary::Periodic: {
                    const int wrapped = high ? 0 : n - 1;
                    side.neighbour = wrapped;
                    side.inverseDistance = 2.0 / (w[size_t(i)] + w[size_t(wrapped)]);
                    break;
                }
                case Boundary::Open:
                    // The ghost's p = 0 lies half a finest cell beyond the face, on every level.
                    side.inverseDistance = 2.0 / (w[size_t(i)] + 1.0);
                    break;
                case Boundary::WallFreeSlip:
                case Boundary::WallNoSlip:
                    break; // not counted: zero normal gradient
                }
            }
        }
    }
}

PressureGrid PressureGrid::finest(glm::ivec3 cells, const std::array<FaceBoundary, 6>& faces,
                                  std::vector<uint8_t> solid) {
    std::array<std::vector<double>, 3> widths;
    for (int a = 0; a < 3; ++a)
        widths[a].assign(size_t(cells[a]), 1.0);
    std::array<Boundary, 6> kinds;
    for (size_t f = 0; f < 6; ++f)
        kinds[f] = faces[f].kind;
    PressureGrid grid(std::move(widths), kinds);
    if (!solid.empty() && solid.size() != size_t(grid.size()))
        throw std::invalid_argument("pressure grid: a solid byte per cell expected");
    grid.solid_ = std::move(solid);
    return grid;
}

Eigen::ArrayXd PressureGrid::withoutSolids(Eigen::ArrayXd v) const {
    for (size_t i = 0; i < solid_.size(); ++i)
        if (solid_[i] != 0) v[Eigen::Index(i)] = 0.0;
    return v;
}

void PressureGrid::neighbourSums(const Eigen::ArrayXd& p, glm::ivec3 q, double& weighted,
                                 double& total) const {
    weighted = 0.0;
    total = 0.0;
    const Eigen::Index here = Eigen::Index(index(q));
    if (solidCell(size_t(here))) return; // no unknown: nothing counted
    // Sides in the order -x, +x, -y, +y, -z, +z, as the Jacobi sweep sums them.
    for (int a = 0; a < 3; ++a)
        for (int high = 0; high < 2; ++high) {
            const Side& side = sides_[a][size_t(high)][size_t(q[a])];
            if (side.inverseDistance == 0.0) continue;
            const Eigen::Index neighbour = here + Eigen::Index(side.neighbour - q[a]) * stride_[a];
            if (side.neighbour >= 0 && solidCell(size_t(neighbour))) continue; // as a wall
            const double c = side.inverseDistance * area(a, q);
            total += c;
            if (side.neighbour >= 0) weighted += c * p[neighbour];
        }
}

Eigen::ArrayXd PressureGrid::apply(const Eigen::ArrayXd& p) const {
    Eigen::ArrayXd result(size());
    for (int k = 0; k < cells_.z; ++k)
        for (int j = 0; j < cells_.y; ++j)
            for (int i = 0; i < cells_.x; ++i) {
                const glm::ivec3 q(i, j, k);
                const Eigen::Index cell = Eigen::Index(index(q));
                double weighted = 0.0, total = 0.0;
                neighbourSums(p, q, weighted, total);
                result[cell] = total * p[cell] - weighted;
            }
    return result;
}

Eigen::ArrayXd PressureGrid::residual(const Eigen::ArrayXd& b, const Eigen::ArrayXd& p) const {
    return b - apply(p);
}

Eigen::SparseMatrix<double> PressureGrid::matrix() const {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(size_t(size()) * 7);
    for (int k = 0; k < cells_.z; ++k)
        for (int j = 0; j < cells_.y; ++j)
            for (int i = 0; i < cells_.x; ++i) {
                const glm::ivec3 q(i, j, k);
                const Eigen::Index row = Eigen::Index(index(q));
                if (solidCell(size_t(row))) continue; // a zero row, as apply() has it
                for (int a = 0; a < 3; ++a)
                    for (int high = 0; high < 2; ++high) {
                        const Side& side = sides_[a][size_t(high)][size_t(q[a])];
                        if (side.inverseDistance == 0.0) continue;
                        glm::ivec3 n = q;
                        n[a] = side.neighbour;
                        if (side.neighbour >= 0 && solidCell(index(n))) continue;
                        const double c = side.inverseDistance * area(a, q);
                        entries.emplace_back(row, row, c);
                        if (side.neighbour < 0) continue;
                        entries.emplace_back(row, Eigen::Index(index(n)), -c);
                    }
            }
    Eigen::SparseMatrix<double> m(size(), size());
    m.setFromTriplets(entries.begin(), entries.end()); // a cell its own neighbour: terms cancel
    return m;
}

Eigen::ArrayXd consistentRightHandSide(const PressureGrid& grid, Eigen::ArrayXd b) {
    if (grid.hasSolids()) {
        b = grid.withoutSolids(std::move(b));
        if (!grid.singular()) return b;
        double sum = 0.0;
        Eigen::Index fluid = 0;
        for (Eigen::Index i = 0; i < b.size(); ++i)
            if (!grid.solidCell(size_t(i))) {
                sum += b[i];
                ++fluid;
            }
        if (fluid == 0) return b;
        const double mean = sum / double(fluid);
        for (Eigen::Index i = 0; i < b.size(); ++i)
            if (!grid.solidCell(size_t(i))) b[i] -= mean;
        return b;
    }
    if (grid.singular() && b.size() > 0) b -= b.mean();
    return b;
}

} // namespace mfx::fluid
