// advectVelocity (docs/fluid.md): semi-Lagrangian, Stam 1999 eq. 7: every face takes the value
// found by tracing its position back through the velocity field over dt (Euler or RK2) and
// sampling its own component there trilinearly, then the per-second drag, u *= exp(-drag * dt).
// Wall-normal faces stay 0.
#include "fluid/reference/reference_solver.h"

#include <cmath>

namespace mfx::fluid {

void ReferenceSolver::advectVelocity() {
    std::array<Eigen::ArrayXd, 3> advected = velocity_;
    const double drag = std::exp(-double(options_.drag) * dt());
    for (int c = 0; c < 3; ++c) {
        const glm::ivec3 n = faceCount(c);
        for (int k = 0; k < n.z; ++k)
            for (int j = 0; j < n.y; ++j)
                for (int i = 0; i < n.x; ++i) {
                    const glm::ivec3 q(i, j, k);
                    double value = 0.0;
                    if (!wallNormalFace(c, q))
                        value = sampleFace(c, velocity_[c], backTrace(facePosition(c, q))) * drag;
                    advected[c][Eigen::Index(faceIndex(c, q))] = flushTiny(value);
                }
    }
    velocity_ = std::move(advected);
}

} // namespace mfx::fluid
