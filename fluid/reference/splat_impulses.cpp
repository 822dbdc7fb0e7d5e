// splatImpulses (docs/fluid.md): every emitter pulls velocity and pigment towards its own values,
// q += a (Q - q) with a = 1 - exp(-strength * falloff * dt) and falloff (1 - d²/r²)² inside the
// radius: frame-rate independent, and never overshooting Q (0 <= a < 1).
#include "fluid/reference/reference_solver.h"

#include <cmath>

namespace mfx::fluid {

namespace {
// Blend weight of emitter `e` at world position `x` over `dt`; 0 outside its radius.
double emitterWeight(const shared::FluidEmitter& e, glm::dvec3 x, double dt) {
    const glm::dvec3 d = x - glm::dvec3(e.positionRadius);
    const double r2 = double(e.positionRadius.w) * double(e.positionRadius.w);
    const double d2 = glm::dot(d, d);
    if (d2 >= r2) return 0.0;
    const double t = 1.0 - d2 / r2;
    return 1.0 - std::exp(-double(e.velocityStrength.w) * t * t * dt);
}
} // namespace

void ReferenceSolver::splatImpulses(std::span<const shared::FluidEmitter> emitters) {
    if (emitters.empty()) return;
    forEachFace([&](int c, glm::ivec3 q) {
        if (wallNormalFace(c, q) || solidFace(c, q)) return; // solid faces keep the solid's
        double& value = velocity_[c][Eigen::Index(faceIndex(c, q))];
        const glm::dvec3 x = facePosition(c, q);
        for (const shared::FluidEmitter& e : emitters) {
            const double a = emitterWeight(e, x, dt());
            value += a * (double(e.velocityStrength[c]) - value);
        }
    });
    for (int k = 0; k < cells_.z; ++k)
        for (int j = 0; j < cells_.y; ++j)
            for (int i = 0; i < cells_.x; ++i) {
                const glm::ivec3 q(i, j, k);
                if (solidCell(q)) continue; // no pigment inside a solid
                const glm::dvec3 x = cellCentre(q);
                for (const shared::FluidEmitter& e : emitters) {
                    const double a = emitterWeight(e, x, dt());
                    for (int channel = 0; channel < 4; ++channel) {
                        double& p = pigment_[Eigen::Index(cellIndex(q) * 4 + size_t(channel))];
                        p += a * (double(e.pigment[channel]) - p);
                    }
                }
            }
}

} // namespace mfx::fluid
