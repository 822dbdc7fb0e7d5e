// advectPigment (docs/fluid.md): semi-Lagrangian advection of the RGBA pigment from cell centres,
// then the per-second fade, pigment *= exp(-fade * dt). Trilinear sampling makes every new value a
// convex combination of old ones: no new extrema.
#include "fluid/reference/reference_solver.h"

#include <cmath>

namespace mfx::fluid {

void ReferenceSolver::advectPigment() {
    Eigen::ArrayXd advected = pigment_;
    const double fade = std::exp(-double(options_.fade) * dt());
    for (int k = 0; k < cells_.z; ++k)
        for (int j = 0; j < cells_.y; ++j)
            for (int i = 0; i < cells_.x; ++i) {
                const glm::ivec3 q(i, j, k);
                const glm::dvec3 source = backTrace(cellCentre(q));
                for (int channel = 0; channel < 4; ++channel)
                    advected[Eigen::Index(cellIndex(q) * 4 + size_t(channel))] =
                        flushTiny(sampleCell(pigment_, source, 4, channel) * fade);
            }
    pigment_ = std::move(advected);
}

} // namespace mfx::fluid
