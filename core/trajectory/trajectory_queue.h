// The trajectory queue (Xu et al., section 4.1): a ring of L segment slots in one GPU buffer.
// Every frame one new segment, between the previous frame's pose and this one, is written into
// the next slot and the oldest live one is dropped, so the trail's cost per frame does not grow
// with its length. No readback on the frame path: the palette goes in through the command buffer,
// the segment is built by a compute pass (shaders/core/build_segment.comp) and stays on the GPU.
//
// Compute shaders writing storage buffers, not a geometry shader with transform feedback: every
// invocation writes a fixed S + 1 vertices (no geometry-output limit to respect), the samples of
// a source vertex are written once and shared by all three kinds through index buffers, and the
// pass needs no rasteriser. The three kinds differ only in how the samples are connected:
//   * Particles: the S + 1 samples of each source vertex, as points;
//   * Lines: a line list joining consecutive samples of each source vertex (S pieces);
//   * Volumes: for every selected triangle, every edge (m, n) and every sub-interval i, the two
//     triangles (S_n[i], S_m[i], S_n[i+1]) and (S_m[i+1], S_n[i+1], S_m[i]) of the prism's side
//     wall (Algorithm 3), indexing the same samples.
//
// The unsplit baseline (method Unsplit, for measurement only) rebuilds every live segment every
// frame from the palettes of the last L + 1 frames (shaders/core/build_trail.comp). Method
// StreamOutput builds the split segment with a geometry shader and transform feedback
// (shaders/build_segment_xfb.*), also for measurement.
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/gpu/timer.h"
#include "core/trajectory/build_segment.h"
#include "core/trajectory/trajectory_kind.h"
#include "core/trajectory/trajectory_source.h"

#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

namespace mfx::trajectory {

// Split: one segment per frame by the compute pass (the queue's method). StreamOutput: the same
// segment by a geometry shader into transform feedback, as the paper did it, for measurement (needs
// geometry shaders and VK_EXT_transform_feedback). Unsplit: the baseline.
enum class Method { Split, StreamOutput, Unsplit };

const char* kindName(Kind kind);
const char* methodName(Method method);

struct QueueOptions {
    Kind kind = Kind::Lines;
    Method method = Method::Split;
    SegmentParameters segment;
    uint32_t lifetime = 16;    // L: frames a segment lives
    uint32_t maxLifetime = 64; // slots allocated; setLifetime may go up to it
};

// What one frame's trajectory pass did.
struct FrameStats {
    uint64_t invocations = 0;         // shader invocations that wrote trajectory vertices
    uint64_t skinningEvaluations = 0; // per-vertex joint blends (dual quaternion skinning)
    uint64_t verticesGenerated = 0;   // trajectory vertices written
    uint64_t bytesWritten = 0;        // by the pass: trajectory vertices, kept transforms, palettes
    uint32_t liveSegments = 0;
};

// A segment the ring holds: its vertices are [firstVertex, firstVertex + verticesPerSegment()).
struct LiveSegment {
    uint64_t frame = 0; // the frame that wrote it (0, 1, 2, ... per record call)
    float birth = 0.0f; // its time
    uint32_t firstVertex = 0;
};

class Queue {
public:
    // Fails (with the reason) on bad options or a ring larger than the device allows.
    static Result<std::unique_ptr<Queue>> create(const gpu::Context& ctx, Source source,
                                                 const QueueOptions& options);

    // Changes L while running (1..maxLifetime). A segment once dropped stays dropped: after a
    // shrink the trail grows back one segment per frame.
    Status setLifetime(uint32_t lifetime);

    // Records this frame: `palette` is the source palette (sourcePalette) at `time`; the segment
    // reaches back to the previous call's time (the first call's segment has no extent). Then a
    // barrier makes the ring visible to vertex input, compute and transfer reads.
    void record(VkCommandBuffer cmd, const std::vector<anim::DualQuatJoint>& palette, float time);

    // A frame passes without a new segment (the effect is outside its time window): the oldest
    // live segment ages out as usual, and the next recorded segment starts afresh (no extent)
    // rather than reaching back across the gap. Split and StreamOutput only (the unsplit baseline
    // rebuilds the trail from every frame's palette; it throws std::logic_error).
    void skip(float time);

    // The segment the last record() wrote (call only after one).
    LiveSegment newestSegment() const;

    // The live segments, newest first.
    std::vector<LiveSegment> liveSegments() const;
    uint32_t verticesPerSegment() const { return sourceVertices_ * (subSamples_ + 1); }
    // A segment holds the S + 1 samples of each source vertex in turn: sample j of source vertex
    // v is vertex firstVertex + v * (S + 1) + j (tau = j / S).
    uint32_t sourceVertices() const { return sourceVertices_; }
    uint32_t subSamples() const { return subSamples_; }
    uint32_t indicesPerSegment() const { return indexCount_; } // 0 for particles
    const gpu::Buffer& vertices() const { return ring_; }
    const gpu::Buffer& indices() const { return indices_; } // empty for particles
    const FrameStats& lastFrame() const { return stats_; }
    // GPU milliseconds of the last recorded pass (waits for it; 0 without timestamp support).
    double lastGpuMilliseconds() const;

    const QueueOptions& options() const { return options_; }
    uint64_t framesRecorded() const { return frames_; }
    // The slot that holds `frame`'s segment if it is live, as the GPU wrote it (waits; tests).
    std::vector<shared::TrajectoryVertex> readSegment(const LiveSegment& segment) const;

private:
    Queue(const gpu::Context& ctx) : ctx_(ctx) {}
    void recordSplit(VkCommandBuffer cmd, const std::vector<shared::SkinJoint>& packed, float time);
    void recordUnsplit(VkCommandBuffer cmd);
    void recordStreamOutput(VkCommandBuffer cmd, const std::vector<shared::SkinJoint>& packed,
                            float time);
    shared::TrajectoryConstants constants() const;
    bool previousWritten() const;

    const gpu::Context& ctx_;
    QueueOptions options_;
    uint32_t sourceVertices_ = 0;
    uint32_t jointCount_ = 0;
    uint32_t subSamples_ = 1;
    uint32_t indexCount_ = 0;
    gpu::Buffer sources_, colours_, transforms_, palette_, times_, ring_, indices_;
    gpu::Program program_;
    std::vector<gpu::DescriptorWrite> resources_; // what program_ binds, for the queue's life
    gpu::GpuTimer timer_;
    PFN_vkCmdBindTransformFeedbackBuffersEXT bindXfb_ = nullptr;
    PFN_vkCmdBeginTransformFeedbackEXT beginXfb_ = nullptr;
    PFN_vkCmdEndTransformFeedbackEXT endXfb_ = nullptr;
    uint64_t frames_ = 0;     // segments recorded so far
    uint64_t oldestLive_ = 0; // the oldest frame whose segment is still live
    float lastTime_ = 0.0f;
    // The times of the last maxLifetime + 1 frames, newest first, and (unsplit) their palettes.
    std::deque<float> historyTimes_;
    std::deque<bool> historyWritten_; // whether each of those frames wrote a segment
    std::deque<std::vector<shared::SkinJoint>> history_;
    FrameStats stats_;
};

} // namespace mfx::trajectory
