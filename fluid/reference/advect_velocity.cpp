// advectVelocity (docs/fluid.md): every face takes its component advected through the velocity
// field over dt by options().advection (semi-Lagrangian, Stam 1999 eq. 7: trace the face position
// back, Euler or RK2, and sample trilinearly; or MacCormack or BFECC built on it, maccormack.cpp
// and bfecc.cpp), then the per-second drag, u *= exp(-drag * dt). Wall-normal faces stay 0. All
// three components are traced through the velocity as it was before the stage.
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
    }
    velocity_ = std::move(advected);
}

} // namespace mfx::fluid
