// The device's memory bandwidth as the benchmarks' yardstick: a buffer-to-buffer copy kernel
// (shaders/core/copy_bandwidth.comp, one vec4 per invocation) timed with timestamp queries. A
// stage that moves B bytes in t seconds reaches B / t, a share of this copy's rate: the roofline
// of a bandwidth-bound kernel.
#pragma once

#include <cstdint>

namespace mfx::gpu {

class Context;

struct CopyBandwidth {
    uint64_t bytes = 0;              // copied each time (read once and written once)
    double medianMs = 0.0;           // median GPU time of one copy (or wall time, below)
    double gigabytesPerSecond = 0.0; // 2 * bytes / medianMs: bytes read plus written
    // A CPU device whose timestamps did not bracket the copy: the wall time of a submission stood
    // in for its GPU time.
    bool fromWallClock = false;
};

// Copies `bytes` (rounded down to 16) `repeats` times after two warm-up copies. Without timestamp
// support the result is all zero.
CopyBandwidth measureCopyBandwidth(const Context& ctx, uint64_t bytes, uint32_t repeats = 10);

} // namespace mfx::gpu
