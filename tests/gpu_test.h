// Fixture for tests that use the GPU: one Context per test suite with the validation layer on.
// Every test fails if the validation layer reported an error during it.
#pragma once

#include "core/gpu/context.h"

#include <gtest/gtest.h>
#include <memory>
#include <string>

namespace mfx::test {

class GpuTest : public ::testing::Test {
protected:
    static void SetUpTestSuite();
    static void TearDownTestSuite();
    void SetUp() override;
    void TearDown() override;

    static gpu::Context& ctx() { return *context_; }
    // Whether the suite's Context exists (for SetUpTestSuite overrides that use it).
    static bool hasContext() { return context_ != nullptr; }

    // Returns the recorded validation messages as one string, for failure output.
    static std::string describeMessages();

private:
    static std::unique_ptr<gpu::Context> context_;
    static std::string creationError_;
};

} // namespace mfx::test
