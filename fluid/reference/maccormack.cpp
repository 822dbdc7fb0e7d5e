// MacCormack advection (docs/fluid.md, "Accuracy options"), after Selle, Fedkiw, Kim, Liu,
// Rossignac, "An Unconditionally Stable MacCormack Method" (J. Sci. Comput. 2008), with A the
// semi-Lagrangian step over dt and A^R the same step over -dt (tracing forwards):
//   phi_hat   = A(phi)                          forward prediction
//   phi_back  = A^R(phi_hat)                    back again; phi - phi_back estimates A's error
//   phi_next  = phi_hat + (phi - phi_back) / 2  second order where the field is smooth
// then limited: phi_next is clamped to the range of the values of phi that A's sample at the same
// point interpolated from (semi_lagrangian.cpp). The clamped value lies between values of phi, so
// pigment keeps the maximum principle. Every trace uses the velocity as it was on entry.
#include "fluid/reference/reference_solver.h"

namespace mfx::fluid {

Eigen::ArrayXd ReferenceSolver::advectMacCormack(int field, const Eigen::ArrayXd& source) const {
    const std::vector<glm::dvec3> backward = departurePoints(field, dt());
    const std::vector<glm::dvec3> forward = departurePoints(field, -dt());
    Eigen::ArrayXd predicted = semiLagrangian(field, source, backward);
    if (options_.storage == Storage::Float16) roundToHalf(predicted); // the GPU's work image
    const Eigen::ArrayXd returned = semiLagrangian(field, predicted, forward);
    Eigen::ArrayXd corrected = predicted + 0.5 * (source - returned);
    clampToSampleRange(field, source, backward, corrected);
    return corrected;
}

} // namespace mfx::fluid
