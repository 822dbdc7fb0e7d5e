#include "core/gpu/timer.h"

#include "core/gpu/check.h"
#include "core/gpu/context.h"

#include <stdexcept>

namespace mfx::gpu {

GpuTimer::GpuTimer(const Context& ctx, uint32_t maxPasses) : maxPasses_(maxPasses) {
    if (!ctx.features().timestamps || maxPasses == 0) return;
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2 * maxPasses;
    VkQueryPool pool = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateQueryPool(ctx.device(), &info, nullptr, &pool));
    pool_ = UniqueQueryPool(ctx.device(), pool);
    periodNs_ = ctx.timestampPeriodNs();

    uint32_t familyCount = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &familyCount, nullptr);
    std::vector<VkQueueFamilyProperties> families(familyCount);
    vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &familyCount, families.data());
    const uint32_t bits = families[ctx.graphicsQueue().family].timestampValidBits;
    validMask_ = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
}

void GpuTimer::reset(VkCommandBuffer cmd) {
    names_.clear();
    open_ = false;
    if (pool_) vkCmdResetQueryPool(cmd, pool_.get(), 0, 2 * maxPasses_);
}

void GpuTimer::begin(VkCommandBuffer cmd, std::string_view passName) {
    if (open_) throw std::logic_error("GpuTimer: pass begun inside another pass");
    if (names_.size() >= maxPasses_)
        throw std::logic_error("GpuTimer: more than " + std::to_string(maxPasses_) + " passes");
    open_ = true;
    const uint32_t index = static_cast<uint32_t>(names_.size());
    names_.push_back(prefix_ + std::string(passName));
    if (pool_)
        vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_.get(), 2 * index);
}

void GpuTimer::end(VkCommandBuffer cmd) {
    if (!open_) throw std::logic_error("GpuTimer: end() without begin()");
    open_ = false;
    const uint32_t index = static_cast<uint32_t>(names_.size()) - 1;
    if (pool_)
        vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_.get(), 2 * index + 1);
}

std::vector<PassTime> GpuTimer::results() const {
    std::vector<PassTime> times;
    if (!pool_ || names_.empty()) return times;
    std::vector<uint64_t> ticks(2 * names_.size());
    MFX_VK_CHECK(
        vkGetQueryPoolResults(pool_.device(), pool_.get(), 0, static_cast<uint32_t>(ticks.size()),
                              ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    for (size_t i = 0; i < names_.size(); ++i) {
        const uint64_t start = ticks[2 * i] & validMask_;
        const uint64_t stop = ticks[2 * i + 1] & validMask_;
        const uint64_t elapsed = (stop - start) & validMask_; // wraps within the valid bits
        times.push_back({names_[i], static_cast<double>(elapsed) * periodNs_ * 1e-6});
    }
    return times;
}

PrimitiveCounter::PrimitiveCounter(const Context& ctx) {
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
    info.queryCount = 1;
    info.pipelineStatistics = VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT;
    VkQueryPool pool = VK_NULL_HANDLE;
    if (vkCreateQueryPool(ctx.device(), &info, nullptr, &pool) == VK_SUCCESS)
        pool_ = UniqueQueryPool(ctx.device(), pool);
}

void PrimitiveCounter::begin(VkCommandBuffer cmd) const {
    if (!valid()) return;
    vkCmdResetQueryPool(cmd, pool_.get(), 0, 1);
    vkCmdBeginQuery(cmd, pool_.get(), 0, 0);
}

void PrimitiveCounter::end(VkCommandBuffer cmd) const {
    if (valid()) vkCmdEndQuery(cmd, pool_.get(), 0);
}

uint64_t PrimitiveCounter::result() const {
    uint64_t count = 0;
    if (valid())
        MFX_VK_CHECK(vkGetQueryPoolResults(pool_.device(), pool_.get(), 0, 1, sizeof count, &count,
                                           sizeof count,
                                           VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    return count;
}

} // namespace mfx::gpu
