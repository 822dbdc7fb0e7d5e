// GPU pass timing with timestamp queries: every pass of a frame is bracketed by begin()/end();
// after the command buffer has finished, results() gives each pass's duration in milliseconds.
#pragma once

#include "core/gpu/handle.h"

#include <string>
#include <string_view>
#include <vector>
#include <vulkan/vulkan.h>

namespace mfx::gpu {

class Context;

struct PassTime {
    std::string name;
    double milliseconds = 0.0;
};

class GpuTimer {
public:
    GpuTimer() = default;
    // Room for `maxPasses` passes per recording. Without timestamp support (see
    // DeviceFeatures::timestamps) the timer records nothing and results() is empty.
    GpuTimer(const Context& ctx, uint32_t maxPasses);

    // Records the reset of all queries; call once per recording, before the first begin().
    void reset(VkCommandBuffer cmd);
    void begin(VkCommandBuffer cmd, std::string_view passName);
    void end(VkCommandBuffer cmd);

    // Put in front of the names of the passes begun from now on (e.g. "smoke0/"), so a component
    // that names its own passes can be told apart from another of its kind.
    void setPrefix(std::string prefix) { prefix_ = std::move(prefix); }

    // Durations of the passes recorded since reset(); waits until they are available.
    std::vector<PassTime> results() const;
    bool enabled() const { return static_cast<bool>(pool_); }

private:
    UniqueQueryPool pool_;
    double periodNs_ = 1.0;
    uint64_t validMask_ = ~0ull;
    uint32_t maxPasses_ = 0;
    std::vector<std::string> names_;
    std::string prefix_;
    bool open_ = false;
};

// Counts the primitives that reach the clipper between begin() and end() of one recording (a
// pipeline-statistics query: clipping invocations). Without the pipelineStatisticsQuery feature
// it is not valid() and counts nothing.
class PrimitiveCounter {
public:
    explicit PrimitiveCounter(const Context& ctx);
    bool valid() const { return static_cast<bool>(pool_); }
    void begin(VkCommandBuffer cmd) const;
    void end(VkCommandBuffer cmd) const;
    // After the recording finished: the count (0 when not valid).
    uint64_t result() const;

private:
    UniqueQueryPool pool_;
};

// Brackets one pass for as long as it lives.
class ScopedPass {
public:
    ScopedPass(GpuTimer& timer, VkCommandBuffer cmd, std::string_view name)
        : timer_(timer), cmd_(cmd) {
        timer_.begin(cmd_, name);
    }
    ~ScopedPass() { timer_.end(cmd_); }
    ScopedPass(const ScopedPass&) = delete;
    ScopedPass& operator=(const ScopedPass&) = delete;

private:
    GpuTimer& timer_;
    VkCommandBuffer cmd_;
};

} // namespace mfx::gpu
