#include "core/gpu/bandwidth.h"

#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/gpu/timer.h"
#include "shaders/embedded.h"

#include <algorithm>
#include <chrono>
#include <vector>

namespace mfx::gpu {

namespace {

struct CopyDispatch {
    uint32_t count;
    uint32_t rowLength;
};

constexpr uint32_t kGroup = 256;

} // namespace

CopyBandwidth measureCopyBandwidth(const Context& ctx, uint64_t bytes, uint32_t repeats) {
    CopyBandwidth result;
    const uint64_t vec4s = bytes / 16;
    if (vec4s == 0 || repeats == 0) return result;
    result.bytes = vec4s * 16;
    const Buffer source = createBuffer(
        ctx, result.bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
        MemoryUsage::DeviceLocal, "bandwidth source");
    const Buffer destination = createBuffer(ctx, result.bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                            MemoryUsage::DeviceLocal, "bandwidth destination");
    ComputeProgramDesc desc;
    desc.name = "copy_bandwidth";
    desc.spirv = shaders::copy_bandwidth_comp;
    desc.pushConstantSize = sizeof(CopyDispatch);
    Program copy = createComputeProgram(ctx, desc);
    // Workgroups in rows of at most the device's x limit.
    const uint64_t groups = (vec4s + kGroup - 1) / kGroup;
    const uint32_t rowGroups =
        uint32_t(std::min<uint64_t>(groups, ctx.limits().maxComputeWorkGroupCount[0]));
    const uint32_t rows = uint32_t((groups + rowGroups - 1) / rowGroups);
    const CopyDispatch push{uint32_t(std::min<uint64_t>(vec4s, UINT32_MAX)), rowGroups * kGroup};

    submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, source.get(), 0, VK_WHOLE_SIZE, 0x3f800000u); // 1.0f everywhere
    });
    GpuTimer timer(ctx, 1);
    std::vector<double> times, walls;
    for (uint32_t run = 0; run < repeats + 2; ++run) {
        const auto wallStart = std::chrono::steady_clock::now();
        submitOneShot(ctx, [&](VkCommandBuffer cmd) {
            timer.reset(cmd);
            timer.begin(cmd, "copy");
            copy.bind(cmd, {bindBuffer(0, source), bindBuffer(1, destination)});
            copy.push(cmd, push);
            vkCmdDispatch(cmd, rowGroups, rows, 1);
            timer.end(cmd);
        });
        const auto passes = timer.results();
        if (passes.empty()) return {};
        if (run >= 2) times.push_back(passes.front().milliseconds);
        const double wall =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wallStart)
                .count();
        if (run >= 2) walls.push_back(wall);
    }
    std::sort(times.begin(), times.end());
    std::sort(walls.begin(), walls.end());
    result.medianMs = times[times.size() / 2];
    // A CPU driver's timestamps may stop bracketing a dispatch (lavapipe's do once graphics work
    // has run in the process: 0.03 ms for a copy that keeps the queue 60 ms): there a time far
    // below the submission's own is not the copy's, and the wall time (record, submit, wait)
    // stands in. On a GPU a small copy is rightly far shorter than its submission.
    const double wallMs = walls[walls.size() / 2];
    if (ctx.info().isCpu() && result.medianMs < 0.1 * wallMs) {
        result.medianMs = wallMs;
        result.fromWallClock = true;
    }
    result.gigabytesPerSecond =
        result.medianMs > 0.0 ? 2.0 * double(result.bytes) / (result.medianMs * 1e6) : 0.0;
    return result;
}

} // namespace mfx::gpu
