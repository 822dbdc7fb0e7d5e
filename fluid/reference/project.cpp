// project (docs/fluid.md): subtract the pressure gradient from every face that is not on a wall,
// u -= (p_high - p_low) / h, with p = 0 across open faces and wrapping across periodic ones. With
// the exact pressure this leaves a discretely divergence-free field.
#include "fluid/reference/reference_solver.h"

namespace mfx::fluid {

void ReferenceSolver::project() {
    // Pressure of a possibly out-of-range cell along `axis`: wrap (periodic) or 0 (open ghost).
    auto pressureAt = [&](glm::ivec3 q, int axis) {
        if (q[axis] >= 0 && q[axis] < cells_[axis]) return pressure_[Eigen::Index(cellIndex(q))];
        if (boundary(axis, false) == Boundary::Periodic) {
            q[axis] = (q[axis] + cells_[axis]) % cells_[axis];
            return pressure_[Eigen::Index(cellIndex(q))];
        }
        return 0.0;
    };
    for (int c = 0; c < 3; ++c) {
        const glm::ivec3 n = faceCount(c);
        for (int k = 0; k < n.z; ++k)
            for (int j = 0; j < n.y; ++j)
                for (int i = 0; i < n.x; ++i) {
                    const glm::ivec3 q(i, j, k);
                    if (wallNormalFace(c, q)) continue;
                    glm::ivec3 below = q;
                    below[c] -= 1;
                    velocity_[c][Eigen::Index(faceIndex(c, q))] -=
                        (pressureAt(q, c) - pressureAt(below, c)) / h_;
                }
    }
}

} // namespace mfx::fluid
