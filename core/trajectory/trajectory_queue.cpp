#include "core/trajectory/trajectory_queue.h"

#include "core/enum_names.h"

#include "core/anim/skin_vertices.h"
#include "core/gpu/context.h"
#include "shaders/embedded.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace mfx::trajectory {

namespace {

constexpr VkDeviceSize kUpdateChunk = 65536; // vkCmdUpdateBuffer's limit per call

// Copies `bytes` into `buffer` at `at` inside the command buffer (no host synchronisation).
void updateBuffer(VkCommandBuffer cmd, const gpu::Buffer& buffer, const void* bytes,
                  VkDeviceSize size, VkDeviceSize at = 0) {
    const auto* data = static_cast<const unsigned char*>(bytes);
    for (VkDeviceSize offset = 0; offset < size; offset += kUpdateChunk)
        vkCmdUpdateBuffer(cmd, buffer.get(), at + offset, std::min(kUpdateChunk, size - offset),
                          data + offset);
}

std::vector<uint32_t> segmentIndices(Kind kind, const Source& source, uint32_t subSamples) {
    const uint32_t per = subSamples + 1;
    std::vector<uint32_t> out;
    if (kind == Kind::Lines) {
        for (uint32_t v = 0; v < source.vertices.size(); ++v)
            for (uint32_t i = 0; i < subSamples; ++i)
                out.insert(out.end(), {v * per + i, v * per + i + 1});
    } else if (kind == Kind::Volumes) {
        for (size_t t = 0; t + 2 < source.triangles.size(); t += 3)
            for (int e = 0; e < 3; ++e) {
                const uint32_t m = source.triangles[t + size_t(e)];
                const uint32_t n = source.triangles[t + size_t((e + 1) % 3)];
                for (uint32_t i = 0; i < subSamples; ++i) {
                    const uint32_t ni = n * per + i, mi = m * per + i;
                    out.insert(out.end(), {ni, mi, ni + 1, mi + 1, ni + 1, mi});
                }
            }
    }
    return out;
}

} // namespace

const char* kindName(Kind kind) {
    static constexpr NamedValue<Kind> kNames[] = {
        {Kind::Particles, "particles"}, {Kind::Lines, "lines"}, {Kind::Volumes, "volumes"}};
    return nameOf(kind, kNames, "lines");
}

const char* methodName(Method method) {
    static constexpr NamedValue<Method> kNames[] = {{Method::Split, "split"},
                                                    {Method::StreamOutput, "split-xfb"},
                                                    {Method::Unsplit, "unsplit"}};
    return nameOf(method, kNames, "split");
}

Result<std::unique_ptr<Queue>> Queue::create(const gpu::Context& ctx, Source source,
                                             const QueueOptions& options) {
    if (Status valid = checkParameters(options.segment); !valid) return valid.error();
    if (options.maxLifetime < 1 || options.maxLifetime > 4096)
        return Error{"maximum lifetime " + std::to_string(options.maxLifetime) +
                     " is outside 1..4096 frames"};
    if (options.lifetime < 1 || options.lifetime > options.maxLifetime)
        return Error{"lifetime " + std::to_string(options.lifetime) + " is outside 1.." +
                     std::to_string(options.maxLifetime) + " frames (the maximum lifetime)"};
    if (source.vertices.empty()) return Error{"the trajectory source has no vertex"};
    if (options.kind == Kind::Volumes && source.triangles.empty())
        return Error{"motion volumes need triangles, and the selection holds none"};
    const bool xfb = options.method == Method::StreamOutput;
    if (xfb && !(ctx.features().geometryShader && ctx.features().transformFeedback))
        return Error{ctx.info().name +
                     " lacks geometry shaders or transform feedback "
                     "(VK_EXT_transform_feedback), which the stream-output method needs"};

    std::unique_ptr<Queue> q(new Queue(ctx));
    q->options_ = options;
    q->sourceVertices_ = uint32_t(source.vertices.size());
    q->jointCount_ = uint32_t(std::max<size_t>(source.palette.size(), 1));
    q->subSamples_ = options.segment.subSamples;
    const VkDeviceSize segmentBytes =
        VkDeviceSize(q->verticesPerSegment()) * sizeof(shared::TrajectoryVertex);
    const VkDeviceSize ringBytes = segmentBytes * options.maxLifetime;
    const VkDeviceSize limit = ctx.limits().maxStorageBufferRange;
    if (ringBytes > limit || uint64_t(q->verticesPerSegment()) * options.maxLifetime > INT32_MAX)
        return Error{"a ring of " + std::to_string(options.maxLifetime) + " segments of " +
                     std::to_string(q->verticesPerSegment()) + " vertices needs " +
                     std::to_string(ringBytes >> 20) + " MiB, more than the device's storage " +
                     "buffer range (" + std::to_string(limit >> 20) +
                     " MiB); use fewer sub-samples, a shorter lifetime or fewer vertices"};

    const VkBufferUsageFlags storage =
        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    q->sources_ = gpu::createBuffer(ctx, source.vertices.size() * sizeof(shared::SkinVertexIn),
                                    storage, gpu::MemoryUsage::DeviceLocal, "trajectory sources");
    gpu::uploadBuffer(ctx, q->sources_, std::span<const shared::SkinVertexIn>(source.vertices));
    q->colours_ = gpu::createBuffer(ctx, source.colours.size() * sizeof(glm::vec4), storage,
                                    gpu::MemoryUsage::DeviceLocal, "trajectory colours");
    gpu::uploadBuffer(ctx, q->colours_, std::span<const glm::vec4>(source.colours));
    q->transforms_ =
        gpu::createBuffer(ctx, 2 * source.vertices.size() * sizeof(shared::SkinJoint), storage,
                          gpu::MemoryUsage::DeviceLocal, "trajectory transforms");
    const VkDeviceSize palettes = options.method == Method::Split ? 1
                                  : options.method == Method::StreamOutput
                                      ? 2
                                      : options.maxLifetime + 1;
    q->palette_ = gpu::createBuffer(ctx, palettes * q->jointCount_ * sizeof(shared::SkinJoint),
                                    storage, gpu::MemoryUsage::DeviceLocal, "trajectory palettes");
    q->times_ = gpu::createBuffer(ctx, (options.maxLifetime + 1) * sizeof(float), storage,
                                  gpu::MemoryUsage::DeviceLocal, "trajectory times");
    q->ring_ = gpu::createBuffer(ctx, ringBytes,
                                 storage | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                     (xfb ? VK_BUFFER_USAGE_TRANSFORM_FEEDBACK_BUFFER_BIT_EXT : 0),
                                 gpu::MemoryUsage::DeviceLocal, "trajectory ring");
    const std::vector<uint32_t> indices = segmentIndices(options.kind, source, q->subSamples_);
    q->indexCount_ = uint32_t(indices.size());
    if (!indices.empty()) {
        q->indices_ =
            gpu::createBuffer(ctx, indices.size() * sizeof(uint32_t),
                              VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                              gpu::MemoryUsage::DeviceLocal, "trajectory indices");
        gpu::uploadBuffer(ctx, q->indices_, std::span<const uint32_t>(indices));
    }

    if (xfb) {
        gpu::GraphicsProgramDesc desc;
        desc.name = "build_segment_xfb";
        desc.vertex = shaders::build_segment_xfb_vert;
        desc.geometry = shaders::build_segment_xfb_geom;
        desc.pushConstantSize = sizeof(shared::TrajectoryConstants);
        desc.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
        desc.rasterizerDiscard = true;
        q->program_ = gpu::createGraphicsProgram(ctx, desc);
        q->resources_ = gpu::bindBuffers({q->palette_, q->sources_, q->colours_});
        q->bindXfb_ = reinterpret_cast<PFN_vkCmdBindTransformFeedbackBuffersEXT>(
            ctx.deviceFunction("vkCmdBindTransformFeedbackBuffersEXT"));
        q->beginXfb_ = reinterpret_cast<PFN_vkCmdBeginTransformFeedbackEXT>(
            ctx.deviceFunction("vkCmdBeginTransformFeedbackEXT"));
        q->endXfb_ = reinterpret_cast<PFN_vkCmdEndTransformFeedbackEXT>(
            ctx.deviceFunction("vkCmdEndTransformFeedbackEXT"));
        if (!q->bindXfb_ || !q->beginXfb_ || !q->endXfb_)
            return Error{ctx.info().name + " does not expose the transform feedback commands"};
    } else {
        gpu::ComputeProgramDesc desc;
        const bool split = options.method == Method::Split;
        desc.name = split ? "build_segment" : "build_trail";
        desc.spirv = split ? shaders::build_segment_comp : shaders::build_trail_comp;
        desc.pushConstantSize = sizeof(shared::TrajectoryConstants);
        q->program_ = gpu::createComputeProgram(ctx, desc);
        q->resources_ = gpu::bindBuffers(
            {q->palette_, q->sources_, q->colours_, split ? q->transforms_ : q->times_, q->ring_});
    }
    q->timer_ = gpu::GpuTimer(ctx, 1);
    return q;
}

Status Queue::setLifetime(uint32_t lifetime) {
    if (lifetime < 1 || lifetime > options_.maxLifetime)
        return Error{"lifetime " + std::to_string(lifetime) + " is outside 1.." +
                     std::to_string(options_.maxLifetime) + " frames (the maximum lifetime)"};
    options_.lifetime = lifetime;
    if (frames_ > 0)
        oldestLive_ = std::max(oldestLive_, frames_ - std::min<uint64_t>(frames_, lifetime));
    return Ok{};
}

shared::TrajectoryConstants Queue::constants() const {
    shared::TrajectoryConstants c{};
    c.vertexCount = sourceVertices_;
    c.jointCount = jointCount_;
    c.subSamples = subSamples_;
    c.impulseScale = options_.segment.impulseScale;
    c.alphaStart = options_.segment.alphaStart;
    c.alphaEnd = options_.segment.alphaEnd;
    c.alphaPower = options_.segment.alphaPower;
    return c;
}

void Queue::record(VkCommandBuffer cmd, const std::vector<anim::DualQuatJoint>& palette,
                   float time) {
    std::vector<shared::SkinJoint> packed = anim::packPalette(palette);
    packed.resize(jointCount_,
                  shared::SkinJoint{glm::vec4(0, 0, 0, 1), glm::vec4(0.0f), glm::vec4(1, 1, 1, 0)});
    timer_.reset(cmd);
    timer_.begin(cmd, methodName(options_.method));
    historyTimes_.push_front(time);
    historyWritten_.push_front(true);
    if (historyTimes_.size() > options_.maxLifetime + 1) {
        historyTimes_.pop_back();
        historyWritten_.pop_back();
    }
    if (options_.method == Method::Split) {
        recordSplit(cmd, packed, time);
    } else if (options_.method == Method::StreamOutput) {
        recordStreamOutput(cmd, packed, time);
    } else {
        history_.push_front(std::move(packed));
        if (history_.size() > options_.maxLifetime + 1) history_.pop_back();
        recordUnsplit(cmd);
    }
    timer_.end(cmd);
    // The transform feedback stage only where the segment was streamed out: a device without
    // the transformFeedback feature (a host's) may not name it.
    const bool streamed = options_.method == Method::StreamOutput;
    gpu::memoryBarrier(
        cmd,
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
            (streamed ? VK_PIPELINE_STAGE_2_TRANSFORM_FEEDBACK_BIT_EXT : 0),
        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
            (streamed ? VK_ACCESS_2_TRANSFORM_FEEDBACK_WRITE_BIT_EXT : 0),
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT |
            VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT |
            VK_ACCESS_2_TRANSFER_READ_BIT);
    lastTime_ = time;
    ++frames_;
    oldestLive_ = std::max(oldestLive_, frames_ - std::min<uint64_t>(frames_, options_.lifetime));
    stats_.liveSegments = 0;
    for (uint64_t age = 0; age < frames_ - oldestLive_; ++age)
        stats_.liveSegments += historyWritten_[size_t(age)] ? 1 : 0;
}

void Queue::recordSplit(VkCommandBuffer cmd, const std::vector<shared::SkinJoint>& packed,
                        float time) {
    // The previous pass may still read the palette and transforms this frame overwrites.
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                       VK_ACCESS_2_TRANSFER_WRITE_BIT);
    updateBuffer(cmd, palette_, packed.data(), packed.size() * sizeof(shared::SkinJoint));
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    shared::TrajectoryConstants c = constants();
    const uint32_t slot = uint32_t(frames_ % options_.maxLifetime);
    c.outputBase = slot * verticesPerSegment();
    c.transformNow = uint32_t(frames_ % 2) * sourceVertices_;
    c.transformPrevious = uint32_t((frames_ + 1) % 2) * sourceVertices_;
    c.hasPrevious = previousWritten() ? 1u : 0u;
    c.time = time;
    c.dt = previousWritten() ? time - lastTime_ : 0.0f;
    program_.bind(cmd, resources_);
    program_.push(cmd, c);
    vkCmdDispatch(cmd, gpu::groupCount(sourceVertices_, MFX_TRAJECTORY_GROUP_SIZE), 1, 1);

    stats_.invocations = sourceVertices_;
    stats_.skinningEvaluations = sourceVertices_;
    stats_.verticesGenerated = verticesPerSegment();
    stats_.bytesWritten = uint64_t(verticesPerSegment()) * sizeof(shared::TrajectoryVertex) +
                          uint64_t(sourceVertices_) * sizeof(shared::SkinJoint) +
                          packed.size() * sizeof(shared::SkinJoint);
}

void Queue::recordStreamOutput(VkCommandBuffer cmd, const std::vector<shared::SkinJoint>& packed,
                               float time) {
    // This frame's palette goes into one half of the buffer; the other half keeps the previous.
    const VkDeviceSize paletteBytes = packed.size() * sizeof(shared::SkinJoint);
    const uint32_t now = uint32_t(frames_ % 2);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                       VK_ACCESS_2_TRANSFER_WRITE_BIT);
    updateBuffer(cmd, palette_, packed.data(), paletteBytes, now * paletteBytes);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    // The previous frame's draws into the ring may still be in flight.
    gpu::memoryBarrier(
        cmd,
        VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
        VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
            VK_ACCESS_2_TRANSFER_READ_BIT,
        VK_PIPELINE_STAGE_2_TRANSFORM_FEEDBACK_BIT_EXT,
        VK_ACCESS_2_TRANSFORM_FEEDBACK_WRITE_BIT_EXT);
    shared::TrajectoryConstants c = constants();
    c.transformNow = now * jointCount_;
    c.transformPrevious = previousWritten() ? (1 - now) * jointCount_ : c.transformNow;
    c.hasPrevious = previousWritten() ? 1u : 0u;
    c.time = time;
    c.dt = previousWritten() ? time - lastTime_ : 0.0f;

    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {1, 1}};
    rendering.layerCount = 1;
    vkCmdBeginRendering(cmd, &rendering);
    const VkViewport viewport{0.0f, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {1, 1}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    program_.bind(cmd, resources_);
    program_.push(cmd, c);
    const VkBuffer ring = ring_.get();
    const VkDeviceSize offset = VkDeviceSize(frames_ % options_.maxLifetime) *
                                verticesPerSegment() * sizeof(shared::TrajectoryVertex);
    const VkDeviceSize size = VkDeviceSize(verticesPerSegment()) * sizeof(shared::TrajectoryVertex);
    bindXfb_(cmd, 0, 1, &ring, &offset, &size);
    beginXfb_(cmd, 0, 0, nullptr, nullptr);
    vkCmdDraw(cmd, sourceVertices_, 1, 0, 0);
    endXfb_(cmd, 0, 0, nullptr, nullptr);
    vkCmdEndRendering(cmd);

    stats_.invocations = sourceVertices_;
    stats_.skinningEvaluations = 2ull * sourceVertices_;
    stats_.verticesGenerated = verticesPerSegment();
    stats_.bytesWritten =
        uint64_t(verticesPerSegment()) * sizeof(shared::TrajectoryVertex) + paletteBytes;
}

void Queue::recordUnsplit(VkCommandBuffer cmd) {
    // Segments of frames oldest..newest after this one is added (the same rule as the split ring).
    const uint64_t newest = frames_;
    const uint64_t oldest =
        std::max(oldestLive_, newest + 1 - std::min<uint64_t>(newest + 1, options_.lifetime));
    const uint32_t segments = uint32_t(newest - oldest + 1);
    // Palettes and times of frames newest, newest - 1, ..., newest - segments; frame -1 is frame 0.
    std::vector<shared::SkinJoint> palettes;
    std::vector<float> times;
    for (uint32_t j = 0; j <= segments; ++j) {
        const size_t k = std::min<size_t>(j, history_.size() - 1);
        palettes.insert(palettes.end(), history_[k].begin(), history_[k].end());
        times.push_back(historyTimes_[k]);
    }
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                       VK_ACCESS_2_TRANSFER_WRITE_BIT);
    updateBuffer(cmd, palette_, palettes.data(), palettes.size() * sizeof(shared::SkinJoint));
    updateBuffer(cmd, times_, times.data(), times.size() * sizeof(float));
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    shared::TrajectoryConstants c = constants();
    c.segmentCount = segments;
    program_.bind(cmd, resources_);
    program_.push(cmd, c);
    vkCmdDispatch(cmd, gpu::groupCount(sourceVertices_, MFX_TRAJECTORY_GROUP_SIZE), segments, 1);

    stats_.invocations = uint64_t(sourceVertices_) * segments;
    stats_.skinningEvaluations = 2ull * sourceVertices_ * segments;
    stats_.verticesGenerated = uint64_t(verticesPerSegment()) * segments;
    stats_.bytesWritten = stats_.verticesGenerated * sizeof(shared::TrajectoryVertex) +
                          palettes.size() * sizeof(shared::SkinJoint) +
                          times.size() * sizeof(float);
}

void Queue::skip(float time) {
    if (options_.method == Method::Unsplit)
        throw std::logic_error("trajectory::Queue::skip: the unsplit baseline records every frame");
    historyTimes_.push_front(time);
    historyWritten_.push_front(false);
    if (historyTimes_.size() > options_.maxLifetime + 1) {
        historyTimes_.pop_back();
        historyWritten_.pop_back();
    }
    ++frames_;
    oldestLive_ = std::max(oldestLive_, frames_ - std::min<uint64_t>(frames_, options_.lifetime));
    stats_ = FrameStats{};
    for (uint64_t age = 0; age < frames_ - oldestLive_; ++age)
        stats_.liveSegments += historyWritten_[size_t(age)] ? 1 : 0;
}

bool Queue::previousWritten() const {
    // Called while recording frame frames_, after its own entry was pushed.
    return frames_ > 0 && historyWritten_.size() > 1 && historyWritten_[1];
}

LiveSegment Queue::newestSegment() const {
    LiveSegment s;
    s.frame = frames_ - 1;
    s.birth = historyTimes_.front();
    s.firstVertex = options_.method == Method::Unsplit
                        ? 0
                        : uint32_t(s.frame % options_.maxLifetime) * verticesPerSegment();
    return s;
}

std::vector<LiveSegment> Queue::liveSegments() const {
    std::vector<LiveSegment> out;
    if (frames_ == 0) return out;
    for (uint64_t frame = frames_; frame-- > oldestLive_;) {
        LiveSegment s;
        s.frame = frame;
        const uint64_t age = frames_ - 1 - frame;
        if (!historyWritten_[size_t(age)]) continue;
        if (options_.method != Method::Unsplit) {
            s.firstVertex = uint32_t(frame % options_.maxLifetime) * verticesPerSegment();
        } else {
            s.firstVertex = uint32_t(age) * verticesPerSegment();
        }
        s.birth = historyTimes_[size_t(age)]; // age < lifetime <= maxLifetime < its size
        out.push_back(s);
    }
    return out;
}

double Queue::lastGpuMilliseconds() const {
    const std::vector<gpu::PassTime> times = timer_.results();
    return times.empty() ? 0.0 : times.front().milliseconds;
}

std::vector<shared::TrajectoryVertex> Queue::readSegment(const LiveSegment& segment) const {
    const std::vector<std::byte> bytes = gpu::readBuffer(ctx_, ring_);
    std::vector<shared::TrajectoryVertex> out(verticesPerSegment());
    std::memcpy(out.data(),
                bytes.data() + size_t(segment.firstVertex) * sizeof(shared::TrajectoryVertex),
                out.size() * sizeof(shared::TrajectoryVertex));
    return out;
}

} // namespace mfx::trajectory
