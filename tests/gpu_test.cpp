#include "tests/gpu_test.h"

namespace mfx::test {

std::unique_ptr<gpu::Context> GpuTest::context_;
std::string GpuTest::creationError_;

void GpuTest::SetUpTestSuite() {
    if (context_) return;
    gpu::ContextOptions options;
    options.validation = true;
    auto created = gpu::Context::create(options);
    if (created)
        context_ = std::move(created).value();
    else
        creationError_ = created.error().message;
}

void GpuTest::TearDownTestSuite() {
    context_.reset();
}

void GpuTest::SetUp() {
    ASSERT_TRUE(context_ != nullptr) << "no Vulkan context: " << creationError_;
    context_->clearValidationMessages();
}

void GpuTest::TearDown() {
    if (!context_) return;
    context_->waitIdle();
    EXPECT_EQ(context_->validationErrorCount(), 0u) << "validation errors during the test:\n"
                                                    << describeMessages();
}

std::string GpuTest::describeMessages() {
    std::string text;
    for (const gpu::ValidationMessage& m : context_->validationMessages())
        text +=
            (m.severity == gpu::MessageSeverity::Error ? "error: " : "warning: ") + m.text + "\n";
    return text;
}

} // namespace mfx::test
