// applyBoundaries (docs/fluid.md): wall-normal faces are 0 (walls do not move along their normal),
// and on a periodic axis the top face repeats face 0.
#include "fluid/reference/reference_solver.h"

namespace mfx::fluid {

void ReferenceSolver::applyBoundaries() {
    for (int c = 0; c < 3; ++c) {
        const glm::ivec3 n = faceCount(c);
        for (int k = 0; k < n.z; ++k)
            for (int j = 0; j < n.y; ++j)
                for (int i = 0; i < n.x; ++i) {
                    const glm::ivec3 q(i, j, k);
                    double& value = velocity_[c][Eigen::Index(faceIndex(c, q))];
                    if (wallNormalFace(c, q)) {
                        value = 0.0;
                    } else if (options_.periodic(c) && q[c] == cells_[c]) {
                        glm::ivec3 first = q;
                        first[c] = 0;
                        value = velocity_[c][Eigen::Index(faceIndex(c, first))];
                    }
                }
    }
}

} // namespace mfx::fluid
