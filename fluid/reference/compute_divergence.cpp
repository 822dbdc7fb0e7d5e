// computeDivergence (docs/fluid.md): div = (u[i+1]-u[i] + v[j+1]-v[j] + w[k+1]-w[k]) / h per cell,
// exact for the MAC grid's face fluxes.
#include "fluid/reference/reference_solver.h"

namespace mfx::fluid {

void ReferenceSolver::computeDivergence() {
    for (int k = 0; k < cells_.z; ++k)
        for (int j = 0; j < cells_.y; ++j)
            for (int i = 0; i < cells_.x; ++i) {
                const glm::ivec3 q(i, j, k);
                double sum = 0.0;
                for (int c = 0; c < 3; ++c) {
                    glm::ivec3 hi = q;
                    hi[c] += 1;
                    sum += velocity_[c][Eigen::Index(faceIndex(c, hi))] -
                           velocity_[c][Eigen::Index(faceIndex(c, q))];
                }
                // A solid cell has no pressure unknown, and so no divergence to remove.
                divergence_[Eigen::Index(cellIndex(q))] = solidCell(q) ? 0.0 : sum / h_;
            }
}

} // namespace mfx::fluid
