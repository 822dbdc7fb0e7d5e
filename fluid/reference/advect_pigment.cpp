// advectPigment (docs/fluid.md): the RGBA pigment at cell centres advected over dt by
// options().advection (semi-Lagrangian, or MacCormack or BFECC with their limiter), then the
// per-second fade, pigment *= exp(-fade * dt). Semi-Lagrangian sampling makes every new value a
// convex combination of old ones, and the limiter clamps the corrected schemes into the range of
// the same old values: no new extrema.
#include "fluid/reference/reference_solver.h"

#include <cmath>

namespace mfx::fluid {

void ReferenceSolver::advectPigment() {
    Eigen::ArrayXd advected = advectField(kPigmentField, pigment_);
    const double fade = std::exp(-double(options_.fade) * dt());
    for (double& value : advected)
        value = flushTiny(value * fade);
    for (size_t cell = 0; cell < solidCells_.size(); ++cell) // none inside a solid
        if (solidCells_[cell] != 0) advected.segment(Eigen::Index(cell * 4), 4) = 0.0;
    pigment_ = std::move(advected);
}

} // namespace mfx::fluid
