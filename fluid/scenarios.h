// Named test scenarios of the smoke solver, shared by `motionfx compare`, `motionfx bench` and
// the tests: each is a complete set of options, an initial state and the emitters of every step.
#pragma once

#include "fluid/solver_options.h"

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mfx::fluid {

struct Scenario {
    std::string name;
    std::string description;
    SolverOptions options;
    FieldState initial;
    // Emitters of step `step` (0-based); may be empty.
    std::function<std::vector<shared::FluidEmitter>(uint32_t step)> emitters;
};

// puff, jet, swirl, random-impulses.
std::span<const char* const> scenarioNames();

// The scenario on a grid of the given cells (cell size 1 / the largest dimension, so the domain's
// longest side is 1 world unit). Unknown names are an error listing the known ones.
Result<Scenario> makeScenario(std::string_view name, glm::uvec3 cells = {32, 32, 32});

} // namespace mfx::fluid
