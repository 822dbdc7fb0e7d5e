// The validation hook: a deliberately invalid Vulkan call must be recorded as an error, which is
// what makes every other GPU test fail on invalid usage; a missing barrier likewise, through the
// layer's synchronisation validation (on in every GPU test); and whole scenes' frames, every
// effect kind with the smoke, record no error and no synchronisation hazard.
#include "tests/gpu_test.h"
#include "tests/scene_render_util.h"

#include "core/gpu/resources.h"

#include <algorithm>
#include <cctype>
#include <functional>

namespace mfx::test {
namespace {

using ValidationHookTest = GpuTest;

// Records `record` into a command buffer that is freed without being submitted: what it checks is
// seen by the validation layer at record time, and the driver never runs it.
void recordOnly(const gpu::Context& ctx, const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = ctx.oneShotPool();
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    ASSERT_EQ(vkAllocateCommandBuffers(ctx.device(), &allocate, &cmd), VK_SUCCESS);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    vkBeginCommandBuffer(cmd, &begin);
    record(cmd);
    vkEndCommandBuffer(cmd);
    vkFreeCommandBuffers(ctx.device(), ctx.oneShotPool(), 1, &cmd);
}

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
    recordOnly(ctx(), [](VkCommandBuffer cmd) { vkCmdDispatch(cmd, 1, 1, 1); });
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

bool anySyncHazard(const std::vector<gpu::ValidationMessage>& messages) {
    return std::any_of(messages.begin(), messages.end(), [](const gpu::ValidationMessage& m) {
        return m.text.find("SYNC-HAZARD") != std::string::npos;
    });
}

TEST_F(ValidationHookTest, CatchesAMissingBarrierBetweenTwoWrites) {
    // Two transfer writes to one buffer with no barrier between them: a write-after-write hazard
    // that only synchronisation validation sees (each call alone is valid). Recorded, never
    // submitted.
    const gpu::Buffer buffer = gpu::createBuffer(ctx(), 256, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                 gpu::MemoryUsage::DeviceLocal, "hazard");
    recordOnly(ctx(), [&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, buffer.get(), 0, VK_WHOLE_SIZE, 1u);
        vkCmdFillBuffer(cmd, buffer.get(), 0, VK_WHOLE_SIZE, 2u);
    });
    EXPECT_TRUE(anySyncHazard(ctx().validationMessages()))
        << "the missing barrier went unnoticed: " << describeMessages();
    ctx().clearValidationMessages();
}

// A scene of docs/scenes played for `frames` frames at a small size under synchronisation
// validation: no error and no hazard of any severity.
class SyncValidation : public GpuTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(SyncValidation, SceneFramesRecordNoHazard) {
    Result<scene::Scene> s = docScene(GetParam());
    ASSERT_TRUE(s.ok()) << s.error().message;
    // The versus scene past its hit (frame 11) and hit-stop: the impact's sparks, flash and ring
    // drawn and its burst written into the smoke's emitters. The textured gallery scenes past
    // their effects' start (frame 30): a ribbon tiled by distance (its distances found and read)
    // and a sheet scrolled and eroded.
    const std::string name = GetParam();
    const uint32_t frames = name == "versus" ? 18 : name.rfind("gallery/texture", 0) == 0 ? 34 : 6;
    s.value().output.frames = frames;
    Result<DrawnScene> drawn = drawScene(ctx(), s.value(), 160, 96);
    ASSERT_TRUE(drawn.ok()) << drawn.error().message;
    drawn.value().playTo(ctx());
    EXPECT_EQ(drawn.value().played, frames);
    EXPECT_EQ(ctx().validationErrorCount(), 0u) << describeMessages();
    EXPECT_FALSE(anySyncHazard(ctx().validationMessages())) << describeMessages();
}

// The hero (toon character, lines, slash arc, smoke, bloom, tone map), "all" (every trail
// effect kind with the smoke), "versus" (two characters, an impact and its burst) and two
// textured ribbons.
INSTANTIATE_TEST_SUITE_P(Scenes, SyncValidation,
                         ::testing::Values("hero", "all", "versus", "gallery/texture_distance",
                                           "gallery/texture_erosion"),
                         [](const ::testing::TestParamInfo<const char*>& test) {
                             std::string name = test.param;
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

} // namespace
} // namespace mfx::test
