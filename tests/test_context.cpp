// Device selection and capability reporting.
#include "core/gpu/context.h"
#include "tests/gpu_test.h"

#include <cstdlib>

namespace mfx::test {
namespace {

using ContextTest = GpuTest;

TEST(ContextSelection, PicksDeviceByCaseInsensitiveNameSubstring) {
    gpu::ContextOptions options;
    options.deviceName = "LLVMPIPE"; // lavapipe is installed wherever the tests run
    auto created = gpu::Context::create(options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    EXPECT_NE(created.value()->info().name.find("llvmpipe"), std::string::npos);
    EXPECT_TRUE(created.value()->info().isCpu());
}

TEST(ContextSelection, UnknownDeviceNameIsAClearErrorListingDevices) {
    gpu::ContextOptions options;
    options.deviceName = "no-such-gpu-9000";
    auto created = gpu::Context::create(options);
    ASSERT_FALSE(created.ok());
    const std::string& message = created.error().message;
    EXPECT_NE(message.find("no Vulkan device matches \"no-such-gpu-9000\""), std::string::npos)
        << message;
    EXPECT_NE(message.find("llvmpipe"), std::string::npos)
        << "should list the devices: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
}

TEST(ContextSelection, EnvironmentVariableChoosesWhenNoNameIsGiven) {
    ::setenv(gpu::kDeviceEnvironmentVariable, "no-such-gpu-9000", 1);
    auto created = gpu::Context::create(gpu::ContextOptions{});
    ::unsetenv(gpu::kDeviceEnvironmentVariable);
    ASSERT_FALSE(created.ok());
    EXPECT_NE(created.error().message.find(gpu::kDeviceEnvironmentVariable), std::string::npos)
        << created.error().message;
}

TEST(ContextSelection, ExplicitNameOverridesEnvironment) {
    ::setenv(gpu::kDeviceEnvironmentVariable, "no-such-gpu-9000", 1);
    gpu::ContextOptions options;
    options.deviceName = "llvmpipe";
    auto created = gpu::Context::create(options);
    ::unsetenv(gpu::kDeviceEnvironmentVariable);
    EXPECT_TRUE(created.ok()) << created.error().message;
}

TEST_F(ContextTest, ReportsLimitsAndQueues) {
    EXPECT_GE(ctx().limits().maxComputeWorkGroupInvocations, 128u);
    EXPECT_GE(ctx().limits().maxImageDimension3D, 256u);
    EXPECT_NE(ctx().graphicsQueue().queue, VK_NULL_HANDLE);
    EXPECT_NE(ctx().computeQueue().queue, VK_NULL_HANDLE);
    EXPECT_EQ(ctx().graphicsQueue().family, ctx().computeQueue().family);
    EXPECT_TRUE(ctx().validationEnabled());
}

TEST(ContextSelection, LavapipeReportsTheFeaturesTheProjectUses) {
    // Mesa 22.3's lavapipe has all of these; a context that failed to query or enable one of them
    // would report false.
    gpu::ContextOptions options;
    options.deviceName = "llvmpipe";
    auto created = gpu::Context::create(options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    const gpu::DeviceFeatures& f = created.value()->features();
    EXPECT_TRUE(f.geometryShader);
    EXPECT_TRUE(f.transformFeedback);
    EXPECT_TRUE(f.shaderFloat16);
    EXPECT_TRUE(f.storageBuffer16BitAccess);
    EXPECT_TRUE(f.bufferFloat32AtomicAdd);
    EXPECT_TRUE(f.imageFloat32AtomicAdd);
    EXPECT_TRUE(f.timestamps);
}

} // namespace
} // namespace mfx::test
