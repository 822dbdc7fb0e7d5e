#include "fluid/field_compare.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mfx::fluid {

namespace {
struct Accumulator {
    double maxAbs = 0.0, errorSquares = 0.0, referenceSquares = 0.0;
    void add(std::span<const float> a, std::span<const float> b) {
        if (a.size() != b.size()) throw std::invalid_argument("difference: sizes differ");
        for (size_t i = 0; i < a.size(); ++i) {
            const double d = double(a[i]) - double(b[i]);
            // A NaN must not hide: it makes the difference infinite.
            const double magnitude = std::isnan(d) ? double(INFINITY) : std::abs(d);
            maxAbs = std::max(maxAbs, magnitude);
            errorSquares += magnitude * magnitude;
            referenceSquares += double(b[i]) * double(b[i]);
        }
    }
    Difference result() const {
        const double error = std::sqrt(errorSquares);
        const double reference = std::sqrt(referenceSquares);
        return {maxAbs, reference > 0.0 ? error / reference : error};
    }
};
} // namespace

double StateDifference::maxRelL2() const {
    return std::max({velocity.relL2, pressure.relL2, divergence.relL2, pigment.relL2});
}

Difference difference(std::span<const float> a, std::span<const float> b) {
    Accumulator acc;
    acc.add(a, b);
    return acc.result();
}

StateDifference difference(const FieldState& a, const FieldState& b) {
    StateDifference d;
    Accumulator velocity;
    velocity.add(a.velocityX, b.velocityX);
    velocity.add(a.velocityY, b.velocityY);
    velocity.add(a.velocityZ, b.velocityZ);
    d.velocity = velocity.result();
    d.pressure = difference(a.pressure, b.pressure);
    d.divergence = difference(a.divergence, b.divergence);
    d.pigment = difference(a.pigment, b.pigment);
    return d;
}

} // namespace mfx::fluid
