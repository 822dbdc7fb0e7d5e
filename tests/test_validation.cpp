// The validation hook: a deliberately invalid Vulkan call must be recorded as an error, which is
// what makes every other GPU test fail on invalid usage.
#include "tests/gpu_test.h"

#include <algorithm>

namespace mfx::test {
namespace {

using ValidationHookTest = GpuTest;

TEST_F(ValidationHookTest, CatchesABufferWithoutUsage) {
    // VUID-VkBufferCreateInfo-usage-requiredbitmask: usage must not be 0.
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = 256;
    info.usage = 0;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    const VkResult result = vkCreateBuffer(ctx().device(), &info, nullptr, &buffer);
    if (result == VK_SUCCESS) vkDestroyBuffer(ctx().device(), buffer, nullptr);

    const std::vector<gpu::ValidationMessage> messages = ctx().validationMessages();
    EXPECT_GE(ctx().validationErrorCount(), 1u) << "the invalid call went unnoticed";
    EXPECT_TRUE(std::any_of(messages.begin(), messages.end(), [](const gpu::ValidationMessage& m) {
        return m.severity == gpu::MessageSeverity::Error &&
               m.text.find("VUID-VkBufferCreateInfo-usage") != std::string::npos;
    })) << describeMessages();
    // Expected failure seen: clear it so the fixture's no-error check passes.
    ctx().clearValidationMessages();
}

TEST_F(ValidationHookTest, CatchesADispatchWithoutAPipeline) {
    // VUID-vkCmdDispatch-None: a dispatch needs a bound compute pipeline. Only recorded, never
    // submitted: the driver must not run it.
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = ctx().oneShotPool();
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    ASSERT_EQ(vkAllocateCommandBuffers(ctx().device(), &allocate, &cmd), VK_SUCCESS);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(cmd, &begin);
    vkCmdDispatch(cmd, 1, 1, 1);
    vkEndCommandBuffer(cmd);
    vkFreeCommandBuffers(ctx().device(), ctx().oneShotPool(), 1, &cmd);
    EXPECT_GE(ctx().validationErrorCount(), 1u) << "the invalid dispatch went unnoticed";
    ctx().clearValidationMessages();
}

TEST_F(ValidationHookTest, ValidUsageRecordsNothing) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = 256;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateBuffer(ctx().device(), &info, nullptr, &buffer), VK_SUCCESS);
    vkDestroyBuffer(ctx().device(), buffer, nullptr);
    EXPECT_EQ(ctx().validationErrorCount(), 0u) << describeMessages();
}

} // namespace
} // namespace mfx::test
