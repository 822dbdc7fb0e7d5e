// The sparse domain in the reference (docs/fluid.md, "Sparse domain"): the dense solver over the
// virtual domain, with everything the sparse grid does not store held at 0. A face is stored when
// a cell beside it is active; an inactive cell is air at rest without pigment, at pressure 0.
// Every stage computes the stored values from values that are 0 where nothing is stored, as the
// GPU's sparse stages do (shaders/fluid/sparse_*.comp); clearInactive() after each stage then
// drops what the dense loops wrote elsewhere. For the stages the sparse domain runs (one read of
// the fields, one write) that is the same as computing the stored values alone; the Jacobi sweeps
// (solve_pressure.cpp) hold inactive cells at p = 0 between sweeps.
#include "fluid/reference/reference_solver.h"

#include <stdexcept>

namespace mfx::fluid {

void ReferenceSolver::setActiveCells(std::vector<uint8_t> activeCells) {
    if (!activeCells.empty()) {
        if (Status valid = validateSparseOptions(options_); !valid)
            throw std::invalid_argument(valid.error().message);
        if (activeCells.size() != size_t(cells_.x) * size_t(cells_.y) * size_t(cells_.z))
            throw std::invalid_argument("the active cells' flags must be one per cell");
    }
    // A face keeps its value only where a cell beside it is active before and after: a face
    // whose bricks on both sides change (one freed, one new) starts again at 0, as a new brick's
    // copy cannot be taken from a brick that no longer has a slot.
    if (!activeCells_.empty() && !activeCells.empty()) {
        auto kept = [&](glm::ivec3 q) {
            const size_t cell = cellIndex(q);
            return activeCells_[cell] != 0 && activeCells[cell] != 0;
        };
        forEachFace([&](int c, glm::ivec3 q) {
            glm::ivec3 below = q;
            below[c] -= 1;
            if ((q[c] < cells_[c] && kept(q)) || (below[c] >= 0 && kept(below))) return;
            velocity_[c][Eigen::Index(faceIndex(c, q))] = 0.0;
        });
    }
    activeCells_ = std::move(activeCells);
    clearInactive();
    markSolids(); // the solids in the new set of cells
}

bool ReferenceSolver::cellActive(glm::ivec3 q) const {
    return activeCells_.empty() || activeCells_[cellIndex(q)] != 0;
}

bool ReferenceSolver::faceStored(int c, glm::ivec3 q) const {
    if (activeCells_.empty()) return true;
    glm::ivec3 below = q;
    below[c] -= 1;
    return (q[c] < cells_[c] && cellActive(q)) || (below[c] >= 0 && cellActive(below));
}

void ReferenceSolver::clearInactive() {
    if (activeCells_.empty()) return;
    forEachFace([&](int c, glm::ivec3 q) {
        if (!faceStored(c, q)) velocity_[c][Eigen::Index(faceIndex(c, q))] = 0.0;
    });
    for (int k = 0; k < cells_.z; ++k)
        for (int j = 0; j < cells_.y; ++j)
            for (int i = 0; i < cells_.x; ++i) {
                const glm::ivec3 q(i, j, k);
                if (cellActive(q)) continue;
                const Eigen::Index cell = Eigen::Index(cellIndex(q));
                pressure_[cell] = 0.0;
                divergence_[cell] = 0.0;
                for (Eigen::Index channel = 0; channel < 4; ++channel)
                    pigment_[4 * cell + channel] = 0.0;
            }
}

} // namespace mfx::fluid
