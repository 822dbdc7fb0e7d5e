// BFECC advection, back and forth error compensation and correction (docs/fluid.md, "Accuracy
// options"), after Kim, Liu, Llamas, Rossignac, "FlowFixer: Using BFECC for Fluid Simulation"
// (Eurographics Workshop on Natural Phenomena 2005), with A the semi-Lagrangian step over dt and
// A^R the same step over -dt (tracing forwards):
//   phi_back  = A^R(A(phi))                     forth and back; phi - phi_back = twice A's error
//   phi_fixed = phi + (phi - phi_back) / 2      the error compensated before advecting
//   phi_next  = A(phi_fixed)
// then limited as MacCormack is (Selle et al. 2008): phi_next is clamped to the range of the values
// of phi that A's sample at the same point interpolates from (semi_lagrangian.cpp), which keeps
// the maximum principle for pigment. Every trace uses the velocity as it was on entry.
#include "fluid/reference/reference_solver.h"

namespace mfx::fluid {

Eigen::ArrayXd ReferenceSolver::advectBfecc(int field, const Eigen::ArrayXd& source) const {
    const std::vector<glm::dvec3> backward = departurePoints(field, dt());
    const std::vector<glm::dvec3> forward = departurePoints(field, -dt());
    // With fp16 storage the two intermediate fields are rounded: the GPU keeps each in a work
    // image.
    const bool half = options_.storage == Storage::Float16;
    Eigen::ArrayXd predicted = semiLagrangian(field, source, backward);
    if (half) roundToHalf(predicted);
    const Eigen::ArrayXd returned = semiLagrangian(field, predicted, forward);
    Eigen::ArrayXd compensated = source + 0.5 * (source - returned);
    if (half) roundToHalf(compensated);
    Eigen::ArrayXd result = semiLagrangian(field, compensated, backward);
    clampToSampleRange(field, source, backward, result);
    return result;
}

} // namespace mfx::fluid
