// advectVelocity (docs/fluid.md): every face takes its component advected through the velocity
// field over dt by options().advection (semi-Lagrangian, Stam 1999 eq. 7: trace the face position
// back, Euler or RK2, and sample trilinearly; or MacCormack or BFECC built on it, maccormack.cpp
// and bfecc.cpp), then the per-second drag, u *= exp(-drag * dt). Wall-normal faces stay 0, and a
// periodic axis's last face takes its first face's value (docs/fluid.md, "Boundaries": after this
// stage every face obeys the boundaries, so no boundary pass runs in a step). All three components
// are traced through the velocity as it was before the stage.
#include "fluid/reference/reference_solver.h"

#include <cmath>

namespace mfx::fluid {

void ReferenceSolver::advectVelocity() {
    std::array<Eigen::ArrayXd, 3> advected;
    const double drag = std::exp(-double(options_.drag) * dt());
    for (int c = 0; c < 3; ++c) {
        advected[c] = advectField(c, velocity_[c]);
        for (double& value : advected[c])
            value = flushTiny(value * drag);
        if (options_.periodic(c)) {
            const glm::ivec3 n = faceCount(c);
            for (int k = 0; k < n.z; ++k)
                for (int j = 0; j < n.y; ++j)
                    for (int i = 0; i < n.x; ++i) {
                        glm::ivec3 last(i, j, k), first(i, j, k);
                        if (last[c] != cells_[c]) continue;
                        first[c] = 0;
                        advected[c][Eigen::Index(faceIndex(c, last))] =
                            advected[c][Eigen::Index(faceIndex(c, first))];
                    }
        }
    }
    keepSolidFaces(advected); // solid faces move with the solid, not with the air
    velocity_ = std::move(advected);
}

} // namespace mfx::fluid
