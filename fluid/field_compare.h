// Differences between two field states (GPU against CPU reference), per field group.
#pragma once

#include "fluid/solver_options.h"

#include <span>

namespace mfx::fluid {

struct Difference {
    double maxAbs = 0.0; // largest |a - b|
    double relL2 = 0.0;  // ||a - b|| / ||b||; ||a - b|| when ||b|| is 0
};

struct StateDifference {
    Difference velocity; // all three components together
    Difference pressure;
    Difference divergence;
    Difference pigment;
    double maxRelL2() const;
};

Difference difference(std::span<const float> a, std::span<const float> b);
// `b` is the reference.
StateDifference difference(const FieldState& a, const FieldState& b);

} // namespace mfx::fluid
