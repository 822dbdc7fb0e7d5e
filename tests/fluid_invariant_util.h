// Helpers shared by the invariant tests (test_fluid_invariants*.cpp): the largest magnitude in a
// field, and a GPU solver made for a test (or the test failed).
#pragma once

#include "fluid/smoke_solver.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <memory>
#include <span>

namespace mfx::test {

inline double maxAbs(std::span<const float> values) {
    double m = 0.0;
    for (float v : values)
        m = std::max(m, std::abs(double(v)));
    return m;
}

inline std::unique_ptr<fluid::SmokeSolver> makeGpu(const gpu::Context& ctx,
                                                   const fluid::SolverOptions& options) {
    auto created = fluid::SmokeSolver::create(ctx, options);
    if (!created.ok()) {
        ADD_FAILURE() << "SmokeSolver::create: " << created.error().message;
        return nullptr;
    }
    return std::move(created).value();
}

} // namespace mfx::test
