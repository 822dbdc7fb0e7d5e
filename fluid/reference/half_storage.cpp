// Storage::Float16 in the reference (docs/fluid.md, "Accuracy options"): the fields a GPU would
// keep in 16-bit images between stages (velocity, pressure, pigment) are rounded to the nearest
// IEEE 754-2008 binary16 value after every stage, while every stage still computes in double. The
// divergence, produced and consumed within one sub-step's projection, keeps full precision.
// Within a stage, what the GPU keeps in a 16-bit image between its passes is rounded too: each
// viscosity sweep (diffuse_viscosity.cpp) and the work fields of MacCormack and BFECC.
//
// binary16: 1 sign bit, 5 exponent bits, 10 fraction bits. Normal values 2^-14 <= |v| <= 65504
// are spaced 2^(e - 10) in the binade [2^e, 2^(e+1)); below 2^-14 the subnormals are spaced
// 2^-24. Rounding is to nearest with ties to even; a magnitude that rounds above 65504 (v >= 65520)
// becomes infinite.
#include "fluid/reference/reference_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mfx::fluid {

double ReferenceSolver::roundToHalf(double v) {
    if (!std::isfinite(v) || v == 0.0) return v;
    int exponent = 0;
    std::frexp(v, &exponent); // |v| = m 2^exponent with m in [0.5, 1): binade 2^(exponent - 1)
    const double spacing = std::ldexp(1.0, std::max(exponent - 1, -14) - 10);
    // v / spacing and the product are exact (powers of two); nearbyint rounds to nearest even in
    // the default rounding mode.
    const double rounded = std::nearbyint(v / spacing) * spacing;
    if (std::abs(rounded) > 65504.0)
        return std::copysign(std::numeric_limits<double>::infinity(), v);
    return rounded;
}

void ReferenceSolver::roundToHalf(Eigen::ArrayXd& values) {
    for (double& v : values)
        v = roundToHalf(v);
}

void ReferenceSolver::roundStoredFields() {
    for (Eigen::ArrayXd* field :
         {&velocity_[0], &velocity_[1], &velocity_[2], &pressure_, &pigment_})
        roundToHalf(*field);
}

} // namespace mfx::fluid
