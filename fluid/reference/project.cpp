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
    forEachFace([&](int c, glm::ivec3 q) {
        if (wallNormalFace(c, q) || solidFace(c, q)) return; // u·n = u_solid·n kept
        glm::ivec3 below = q;
        below[c] -= 1;
        velocity_[c][Eigen::Index(faceIndex(c, q))] -=
            (pressureAt(q, c) - pressureAt(below, c)) / h_;
    });
}

} // namespace mfx::fluid
