// applyBoundaries (docs/fluid.md): wall-normal faces are 0 (walls do not move along their normal),
// and on a periodic axis the top face repeats face 0.
#include "fluid/reference/reference_solver.h"

namespace mfx::fluid {

void ReferenceSolver::applyBoundaries() {
    forEachFace([&](int c, glm::ivec3 q) {
        double& value = velocity_[c][Eigen::Index(faceIndex(c, q))];
        if (wallNormalFace(c, q)) {
            value = 0.0;
        } else if (options_.periodic(c) && q[c] == cells_[c]) {
            glm::ivec3 first = q;
            first[c] = 0;
            value = velocity_[c][Eigen::Index(faceIndex(c, first))];
        }
    });
}

} // namespace mfx::fluid
