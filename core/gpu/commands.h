// Command buffers: one-shot (record, submit, wait; for set-up and readback) and reusable (one per
// frame in flight, with its own fence).
#pragma once

#include "core/gpu/handle.h"

#include <functional>
#include <vulkan/vulkan.h>

namespace mfx::gpu {

class Context;
struct Queue;

// Records commands with `record` into a fresh command buffer, submits it to the graphics queue
// and waits for it to finish.
void submitOneShot(const Context& ctx, const std::function<void(VkCommandBuffer)>& record);

// A command buffer recorded again and again: begin() waits for the previous submission to finish
// and resets it, so the buffer can be re-recorded every frame.
class CommandBuffer {
public:
    CommandBuffer() = default;
    ~CommandBuffer(); // waits for a pending submission before freeing the pool
    CommandBuffer(CommandBuffer&& other) noexcept;
    CommandBuffer& operator=(CommandBuffer&& other) noexcept;
    static CommandBuffer create(const Context& ctx, const Queue& queue);

    VkCommandBuffer begin(); // waits for the previous submission, then begins recording
    void end();
    // Submits to the queue given at creation; signals the internal fence (and `signal`, if any),
    // after waiting on `wait` at `waitStage`, if any.
    void submit(VkSemaphore wait = VK_NULL_HANDLE,
                VkPipelineStageFlags2 waitStage = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                VkSemaphore signal = VK_NULL_HANDLE);
    void wait(); // until the last submission finished (no-op if none is pending)

    VkCommandBuffer get() const { return cmd_; }

private:
    UniqueCommandPool pool_;
    UniqueFence fence_;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    bool pending_ = false;
};

} // namespace mfx::gpu
