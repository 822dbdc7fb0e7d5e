// applyBuoyancy (docs/fluid.md): v += dt * buoyancy * (pigment alpha averaged over the two cells
// beside the face), an upward (+y) acceleration where there is smoke. Off when buoyancy is 0.
#include "fluid/reference/reference_solver.h"

namespace mfx::fluid {

void ReferenceSolver::applyBuoyancy() {
    if (options_.buoyancy == 0.0f) return;
    const glm::ivec3 n = faceCount(1);
    for (int k = 0; k < n.z; ++k)
        for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i) {
                const glm::ivec3 q(i, j, k);
                if (wallNormalFace(1, q) || solidFace(1, q)) continue;
                const double density = 0.5 * (fetchCell(pigment_, q - glm::ivec3(0, 1, 0), 4, 3) +
                                              fetchCell(pigment_, q, 4, 3));
                velocity_[1][Eigen::Index(faceIndex(1, q))] +=
                    dt() * double(options_.buoyancy) * density;
            }
}

} // namespace mfx::fluid
