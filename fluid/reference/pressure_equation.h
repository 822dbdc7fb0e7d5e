// The pressure equation of the projection (docs/fluid.md, step 10 and "Accuracy options") on a grid
// of cells of possibly unequal widths: the simulation grid itself, where every cell is one unit
// wide and the equation is exactly the one the Jacobi sweep solves, or a coarser level of the
// multigrid hierarchy, whose cells cover up to 2x2x2 cells of the level below. Used by the
// red-black Gauss-Seidel, multigrid and MGPCG solvers of the CPU reference and by its residual
// measurement.
//
// The operator is the finite-volume discretisation of -Laplacian (Bridson 2015, ch. 5, for the
// unit-width grid; Trottenberg, Oosterlee, Schueller, "Multigrid", 2001, ch. 2, for rediscretising
// on coarse levels):
//   (A p)_q = sum over the sides of q of c_s (p_q - p_n(s)),
//   c_s = (area of the side) / (distance between the two centres), in units of the finest cell,
// where the neighbour n(s) is the cell across the side, wraps on a periodic axis, is a ghost with
// p = 0 half a finest cell beyond an open face (distance (w_q + 1) / 2), and does not exist across
// a wall (c_s = 0). On the finest grid every counted c_s is 1: A p = count p - sum p_n.
//
// Solids (docs/fluid.md, "Solids"), on the finest grid only: a solid cell has no unknown (its row
// of A is 0 and its p stays 0) and a side towards a solid cell is not counted (c_s = 0: zero
// normal gradient, as at a wall), the equation the Jacobi sweep solves. The coarse levels of the
// multigrid hierarchy do not see the solids (their operators are the solid-free ones): the V-cycle
// stays a symmetric positive definite preconditioner, which is all MGPCG needs, and converges more
// slowly next to solids; prolonged corrections are set to 0 in the solid cells.
#pragma once

#include "fluid/solver_options.h"

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace mfx::fluid {

// The centres of cells of the given widths along one axis, measured from the axis' low face.
std::vector<double> cellCentres(const std::vector<double>& widths);

class PressureGrid {
public:
    // A grid whose cells along axis a have widths[a] (in finest cells), with the six domain faces
    // of the simulation (-x, +x, -y, +y, -z, +z).
    PressureGrid(std::array<std::vector<double>, 3> widths, std::array<Boundary, 6> boundaries);
    // The simulation grid: `cells` cells of width 1; `solid` one byte per cell (x-fastest,
    // nonzero: solid), or empty without solids.
    static PressureGrid finest(glm::ivec3 cells, const std::array<FaceBoundary, 6>& boundaries,
                               std::vector<uint8_t> solid = {});

    glm::ivec3 cells() const { return cells_; }
    Eigen::Index size() const { return Eigen::Index(cells_.x) * cells_.y * cells_.z; }
    const std::vector<double>& widths(int axis) const { return widths_[axis]; }
    const std::array<Boundary, 6>& boundaries() const { return boundaries_; }
    // No open face: A is singular, with the constants as its null space; A p = b has a solution
    // exactly when b sums to 0.
    bool singular() const { return singular_; }
    bool hasSolids() const { return !solid_.empty(); }
    bool solidCell(size_t index) const { return !solid_.empty() && solid_[index] != 0; }
    // v with its solid cells set to 0.
    Eigen::ArrayXd withoutSolids(Eigen::ArrayXd v) const;
    size_t index(glm::ivec3 q) const {
        return size_t(q.x) + size_t(cells_.x) * (size_t(q.y) + size_t(cells_.y) * size_t(q.z));
    }

    Eigen::ArrayXd apply(const Eigen::ArrayXd& p) const;                             // A p
    Eigen::ArrayXd residual(const Eigen::ArrayXd& b, const Eigen::ArrayXd& p) const; // b - A p
    // A as a sparse matrix (for the exact coarsest solve and for checks).
    Eigen::SparseMatrix<double> matrix() const;

    // Gauss-Seidel over the cells of one colour (0 red: i+j+k even, 1 black):
    //   p_q <- (sum_s c_s p_n(s) + b_q) / sum_s c_s   (0 where nothing is counted),
    // every update reading the values as they stood before the half-sweep
    // (red_black_gauss_seidel.cpp).
    void relaxColour(Eigen::ArrayXd& p, const Eigen::ArrayXd& b, int colour) const;
    // `sweeps` sweeps, each the red cells then the black ones, or black then red when
    // `blackFirst` (the reverse order, which makes a pre- and post-smoother pair symmetric).
    void redBlackSweeps(Eigen::ArrayXd& p, const Eigen::ArrayXd& b, uint32_t sweeps,
                        bool blackFirst = false) const;

    // One side of a cell along one axis: the neighbour's index along that axis (-1: none, an open
    // ghost with p = 0 or a wall) and 1 / distance between the centres (0 across a wall).
    struct Side {
        int neighbour = -1;
        double inverseDistance = 0.0;
    };
    // The low (high = false) or high side along `axis` of the cells whose index along it is `i`.
    const Side& side(int axis, bool high, int i) const {
        return sides_[size_t(axis)][high ? 1 : 0][size_t(i)];
    }

private:
    // sum_s c_s p_n(s) and sum_s c_s of cell q.
    void neighbourSums(const Eigen::ArrayXd& p, glm::ivec3 q, double& weighted,
                       double& total) const;
    double area(int axis, glm::ivec3 q) const {
        const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        return widths_[a1][size_t(q[a1])] * widths_[a2][size_t(q[a2])];
    }

    glm::ivec3 cells_;
    std::array<std::vector<double>, 3> widths_;
    std::array<Boundary, 6> boundaries_;
    bool singular_ = true;
    std::array<std::array<std::vector<Side>, 2>, 3> sides_; // [axis][low, high][index along axis]
    glm::ivec3 stride_;
    std::vector<uint8_t> solid_; // per cell, empty without solids
};

// b with its mean removed when the grid is singular (its part in the range of A), else b; with
// solids, the mean over the fluid cells removed from them and the solid cells 0.
Eigen::ArrayXd consistentRightHandSide(const PressureGrid& grid, Eigen::ArrayXd b);

// The multigrid hierarchy of a pressure grid and its V-cycle (multigrid.cpp).
class Multigrid {
public:
    // `levels` grids, the finest included (0, or more than possible: every level down to 2 cells
    // on each axis that started with more than 1).
    Multigrid(const PressureGrid& finest, uint32_t levels);
    ~Multigrid();

    size_t levelCount() const { return levels_.size(); }
    const PressureGrid& level(size_t l) const { return levels_[l]; }

    // Which transfers and smoothing order a V-cycle uses.
    enum class Cycle {
        // The multigrid solver: restriction R0 (each coarse cell sums the residuals of the fine
        // cells it covers), pre- and post-smoothing both red then black.
        Standard,
        // The MGPCG preconditioner: restriction P^T, pre-smoothing red then black and
        // post-smoothing black then red, so that with equal counts and x = 0 on entry x = M b
        // with M symmetric.
        Symmetric,
    };
    // One V-cycle on A x = b at the finest level, improving x in place: `preSmooth` sweeps, the
    // residual restricted, the coarse correction (recursively, exact on the coarsest level)
    // prolonged by P and added, `postSmooth` sweeps.
    void vCycle(Eigen::ArrayXd& x, const Eigen::ArrayXd& b, uint32_t preSmooth, uint32_t postSmooth,
                Cycle kind) const;

    // The transfer operators between level l and level l + 1: P, trilinear interpolation of a
    // coarse correction at the fine cell centres; its transpose P^T; and R0, the sum over the fine
    // cells each coarse cell covers.
    Eigen::ArrayXd prolong(size_t l, const Eigen::ArrayXd& coarse) const;
    Eigen::ArrayXd restrictTranspose(size_t l, const Eigen::ArrayXd& fine) const;
    Eigen::ArrayXd restrictSum(size_t l, const Eigen::ArrayXd& fine) const;
    // The exact solution on the coarsest level (mean-free when singular).
    Eigen::ArrayXd solveCoarsest(const Eigen::ArrayXd& b) const;

    // How a fine cell's index along one axis interpolates from the coarse level: up to two coarse
    // indices (-1: an open ghost, value 0, or nothing) with their weights.
    struct Interpolation {
        int coarse[2] = {-1, -1};
        double weight[2] = {0.0, 0.0};
    };
    // Along `axis`, per index of level l: how it interpolates from level l + 1, and the index of
    // the level l + 1 cell covering it (the GPU solver's tables are made from these).
    const std::vector<Interpolation>& interpolation(size_t l, int axis) const {
        return interpolation_[l][size_t(axis)];
    }
    const std::vector<int>& parents(size_t l, int axis) const { return parent_[l][size_t(axis)]; }

private:
    void cycle(size_t l, Eigen::ArrayXd& x, const Eigen::ArrayXd& b, uint32_t preSmooth,
               uint32_t postSmooth, Cycle kind) const;

    std::vector<PressureGrid> levels_;
    // interpolation_[l][axis][fine index]: level l from level l + 1.
    std::vector<std::array<std::vector<Interpolation>, 3>> interpolation_;
    // parent_[l][axis][fine index]: the coarse index of the cell covering it.
    std::vector<std::array<std::vector<int>, 3>> parent_;
    std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> coarsest_;
};

} // namespace mfx::fluid
