#include "core/gpu/commands.h"

#include "core/gpu/check.h"
#include "core/gpu/context.h"

#include <utility>

namespace mfx::gpu {

void submitOneShot(const Context& ctx, const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = ctx.oneShotPool();
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkAllocateCommandBuffers(ctx.device(), &allocate, &cmd));
    // Free the command buffer on every path out, including an exception from `record`.
    struct Release {
        VkDevice device;
        VkCommandPool pool;
        VkCommandBuffer cmd;
        ~Release() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
    } release{ctx.device(), ctx.oneShotPool(), cmd};

    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    MFX_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    MFX_VK_CHECK(vkEndCommandBuffer(cmd));

    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fenceHandle = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateFence(ctx.device(), &fenceInfo, nullptr, &fenceHandle));
    UniqueFence fence(ctx.device(), fenceHandle);

    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    MFX_VK_CHECK(vkQueueSubmit2(ctx.graphicsQueue().queue, 1, &submit, fence.get()));
    MFX_VK_CHECK(vkWaitForFences(ctx.device(), 1, &fenceHandle, VK_TRUE, UINT64_MAX));
}

CommandBuffer CommandBuffer::create(const Context& ctx, const Queue& queue) {
    CommandBuffer result;
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = queue.family;
    VkCommandPool pool = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateCommandPool(ctx.device(), &poolInfo, nullptr, &pool));
    result.pool_ = UniqueCommandPool(ctx.device(), pool);

    VkCommandBufferAllocateInfo allocate{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocate.commandPool = pool;
    allocate.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocate.commandBufferCount = 1;
    MFX_VK_CHECK(vkAllocateCommandBuffers(ctx.device(), &allocate, &result.cmd_));

    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateFence(ctx.device(), &fenceInfo, nullptr, &fence));
    result.fence_ = UniqueFence(ctx.device(), fence);
    result.queue_ = queue.queue;
    return result;
}

CommandBuffer::~CommandBuffer() {
    if (pending_) {
        VkFence fence = fence_.get();
        vkWaitForFences(fence_.device(), 1, &fence, VK_TRUE, UINT64_MAX);
    }
}

CommandBuffer::CommandBuffer(CommandBuffer&& other) noexcept
    : pool_(std::move(other.pool_)), fence_(std::move(other.fence_)),
      cmd_(std::exchange(other.cmd_, VK_NULL_HANDLE)), queue_(other.queue_),
      pending_(std::exchange(other.pending_, false)) {}

CommandBuffer& CommandBuffer::operator=(CommandBuffer&& other) noexcept {
    if (this != &other) {
        if (pending_) wait();
        fence_ = std::move(other.fence_);
        pool_ = std::move(other.pool_);
        cmd_ = std::exchange(other.cmd_, VK_NULL_HANDLE);
        queue_ = other.queue_;
        pending_ = std::exchange(other.pending_, false);
    }
    return *this;
}

VkCommandBuffer CommandBuffer::begin() {
    wait();
    MFX_VK_CHECK(vkResetCommandBuffer(cmd_, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    MFX_VK_CHECK(vkBeginCommandBuffer(cmd_, &begin));
    return cmd_;
}

void CommandBuffer::end() {
    MFX_VK_CHECK(vkEndCommandBuffer(cmd_));
}

void CommandBuffer::submit(VkSemaphore wait, VkPipelineStageFlags2 waitStage, VkSemaphore signal) {
    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = cmd_;
    VkSemaphoreSubmitInfo waitInfo{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    waitInfo.semaphore = wait;
    waitInfo.stageMask = waitStage;
    VkSemaphoreSubmitInfo signalInfo{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signalInfo.semaphore = signal;
    signalInfo.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;

    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.waitSemaphoreInfoCount = wait != VK_NULL_HANDLE ? 1 : 0;
    submit.pWaitSemaphoreInfos = &waitInfo;
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    submit.signalSemaphoreInfoCount = signal != VK_NULL_HANDLE ? 1 : 0;
    submit.pSignalSemaphoreInfos = &signalInfo;
    VkFence fence = fence_.get();
    MFX_VK_CHECK(vkResetFences(fence_.device(), 1, &fence));
    MFX_VK_CHECK(vkQueueSubmit2(queue_, 1, &submit, fence));
    pending_ = true;
}

void CommandBuffer::wait() {
    if (!pending_) return;
    VkFence fence = fence_.get();
    MFX_VK_CHECK(vkWaitForFences(fence_.device(), 1, &fence, VK_TRUE, UINT64_MAX));
    pending_ = false;
}

} // namespace mfx::gpu
