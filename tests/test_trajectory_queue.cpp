// The GPU trajectory queue: its pass against the CPU twin, welding of consecutive segments, the
// ring's behaviour as segments are born and age out, and the methods and kinds agreeing.
#include "core/anim/fighter.h"
#include "core/anim/sampling.h"
#include "core/gpu/commands.h"
#include "core/trajectory/build_segment.h"
#include "core/trajectory/trajectory_queue.h"
#include "core/trajectory/trajectory_source.h"
#include "tests/gpu_test.h"
#include "tests/trajectory_test_util.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/quaternion.hpp>
#include <memory>
#include <string>
#include <vector>

namespace mfx::test {
namespace {

using trajectory::Source;

using TrajectoryGpu = GpuTest;

std::unique_ptr<trajectory::Queue> makeQueue(gpu::Context& ctx, Source source,
                                             trajectory::QueueOptions options) {
    auto created = trajectory::Queue::create(ctx, std::move(source), options);
    EXPECT_TRUE(created.ok()) << created.error().message;
    return created ? std::move(created).value() : nullptr;
}

// The fighter's palette at `time` in `clip`.
std::vector<anim::DualQuatJoint> fighterPalette(const anim::Character& fighter,
                                                const Source& source, const anim::Clip& clip,
                                                float time) {
    return trajectory::sourcePalette(fighter, source,
                                     anim::samplePose(fighter, &clip, time, anim::Wrap::Clamp));
}

TEST_F(TrajectoryGpu, SegmentEqualsTheCpuTwin) {
    const anim::Character fighter = anim::makeFighter();
    trajectory::Selection selection;
    selection.bones = {"thigh_r", "shin_r", "foot_r", "toe_r"};
    Source source = trajectory::selectSource(fighter, selection).value();
    trajectory::QueueOptions options;
    options.segment.subSamples = 6;
    options.segment.impulseScale = 0.8f;
    options.segment.alphaPower = 1.5f;
    options.lifetime = 4;
    options.maxLifetime = 4;
    auto queue = makeQueue(ctx(), source, options);
    ASSERT_TRUE(queue);
    const anim::Clip& kick = *fighter.findClip("roundhouse_kick");
    const float dt = 1.0f / 30.0f;
    const float t0 = 0.40f, t1 = t0 + dt;
    const auto p0 = fighterPalette(fighter, source, kick, t0);
    const auto p1 = fighterPalette(fighter, source, kick, t1);
    gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
        queue->record(cmd, p0, t0);
        queue->record(cmd, p1, t1);
    });
    const auto live = queue->liveSegments();
    ASSERT_EQ(live.size(), 2u);
    const auto gpu = queue->readSegment(live[0]);
    const auto cpu = trajectory::buildSegment(source, trajectory::vertexTransforms(source, p1),
                                              trajectory::vertexTransforms(source, p0), t1, t1 - t0,
                                              options.segment);
    ASSERT_EQ(gpu.size(), cpu.size());
    double worstPosition = 0, worstNormal = 0, worstVelocity = 0, worstAlpha = 0, fastest = 0;
    double velocityError2 = 0, velocity2 = 0;
    for (size_t i = 0; i < cpu.size(); ++i) {
        worstPosition =
            std::max(worstPosition,
                     double(glm::length(glm::vec3(gpu[i].position) - glm::vec3(cpu[i].position))));
        worstNormal = std::max(
            worstNormal, double(glm::length(glm::vec3(gpu[i].normal) - glm::vec3(cpu[i].normal))));
        const glm::dvec3 dv =
            glm::dvec3(glm::vec3(gpu[i].velocity)) - glm::dvec3(glm::vec3(cpu[i].velocity));
        worstVelocity = std::max(worstVelocity, glm::length(dv));
        velocityError2 += glm::dot(dv, dv);
        const glm::dvec3 v(glm::vec3(cpu[i].velocity));
        velocity2 += glm::dot(v, v);
        fastest = std::max(fastest, glm::length(v));
        worstAlpha = std::max(worstAlpha, double(std::abs(gpu[i].color.a - cpu[i].color.a)));
        ASSERT_EQ(gpu[i].velocity.w, t1);
        ASSERT_EQ(gpu[i].position.w, cpu[i].position.w);
    }
    const double velocityRelL2 = std::sqrt(velocityError2 / velocity2);
    std::printf("%zu trajectory vertices: GPU vs CPU position %.3g m, normal %.3g, alpha %.3g; "
                "velocity relative L2 %.3g, largest difference %.3g m/s (fastest %.3g m/s)\n",
                cpu.size(), worstPosition, worstNormal, worstAlpha, velocityRelL2, worstVelocity,
                fastest);
    EXPECT_GT(fastest, 1.0); // the kick moves: not a vacuous comparison
    EXPECT_LE(worstPosition, 1e-5);
    EXPECT_LE(worstNormal, 1e-5);
    EXPECT_LE(worstAlpha, 1e-5);
    EXPECT_LE(velocityRelL2, 1e-5);
    // Per sample, a velocity is the difference of two positions about 1 m from the origin times
    // S / dt = 180: one ulp of such a position (1.2e-7 m) is already 2e-5 m/s, 4e-6 of the fastest
    // speed. So a single sample can only be held to a few ulps: 5e-5 of the fastest speed.
    EXPECT_LE(worstVelocity, 5e-5 * fastest);
}

// The same 90-degree turn through the GPU queue: its sub-samples lie on the arc too.
TEST_F(TrajectoryGpu, RotationFollowsTheArc) {
    const float radius = 0.8f;
    trajectory::QueueOptions options;
    options.segment.subSamples = 16;
    options.lifetime = 2;
    options.maxLifetime = 2;
    auto queue = makeQueue(ctx(), ringSource(16, radius), options);
    ASSERT_TRUE(queue);
    const glm::vec3 up(0, 1, 0);
    gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
        queue->record(cmd, {rigid(glm::quat(1, 0, 0, 0), glm::vec3(0.0f))}, 0.0f);
        queue->record(cmd, {rigid(glm::angleAxis(glm::radians(90.0f), up), glm::vec3(0.0f))},
                      1.0f / 30.0f);
    });
    const auto segment = queue->readSegment(queue->liveSegments().front());
    double worst = 0.0, swept = 0.0;
    for (size_t v = 0; v < 16; ++v) {
        const glm::vec3 a(segment[v * 17].position), b(segment[v * 17 + 16].position);
        swept = std::max(swept, double(glm::length(a - b)));
        for (size_t i = 0; i <= 16; ++i) {
            const glm::vec3 p(segment[v * 17 + i].position);
            worst = std::max(worst, double(std::abs(glm::length(glm::vec2(p.x, p.z)) - radius)));
        }
    }
    EXPECT_GT(swept, 1.1 * double(radius)); // the chord of a quarter turn is r * sqrt(2)
    EXPECT_LT(worst, 1e-4 * double(radius));
}

// Segment i's tau = 1 end is segment i-1's tau = 0 end, bit for bit, for every source vertex of
// the whole fighter, across 100 frames of every clip.
TEST_F(TrajectoryGpu, WeldingIsExactAcross100FramesOfEveryClip) {
    const anim::Character fighter = anim::makeFighter();
    Source source = trajectory::selectSource(fighter, {}).value();
    const size_t sources = source.vertices.size();
    trajectory::QueueOptions options;
    options.segment.subSamples = 2;
    options.lifetime = 100;
    options.maxLifetime = 100;
    for (const anim::Clip& clip : fighter.clips) {
        auto queue = makeQueue(ctx(), source, options);
        ASSERT_TRUE(queue);
        const float dt = clip.duration / 100.0f; // the whole clip in 100 frames
        gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
            for (int f = 0; f < 100; ++f) {
                const float t = float(f) * dt;
                queue->record(cmd, fighterPalette(fighter, source, clip, t), t);
            }
        });
        const auto live = queue->liveSegments();
        ASSERT_EQ(live.size(), 100u);
        const std::vector<std::byte> ring = gpu::readBuffer(ctx(), queue->vertices());
        auto sample = [&](const trajectory::LiveSegment& s, size_t v, size_t i) {
            shared::TrajectoryVertex out;
            std::memcpy(
                &out, ring.data() + (s.firstVertex + v * 3 + i) * sizeof(shared::TrajectoryVertex),
                sizeof(out));
            return out;
        };
        size_t mismatches = 0;
        double moved = 0.0;
        for (size_t k = 0; k + 1 < live.size(); ++k) { // live[k] is newer than live[k + 1]
            for (size_t v = 0; v < sources; ++v) {
                const shared::TrajectoryVertex end = sample(live[k], v, 2);
                const shared::TrajectoryVertex start = sample(live[k + 1], v, 0);
                if (std::memcmp(&end.position, &start.position, 12) != 0 ||
                    std::memcmp(&end.normal, &start.normal, 12) != 0)
                    ++mismatches;
                moved =
                    std::max(moved, double(glm::length(glm::vec3(sample(live[k], v, 0).position) -
                                                       glm::vec3(end.position))));
            }
        }
        EXPECT_EQ(mismatches, 0u) << clip.name << ": " << sources * 99 << " welds";
        EXPECT_GT(moved, 1e-4) << clip.name << " should move"; // idle moves ~1 mm a frame
    }
}

// The births read back from every live slot are those of the frames the queue says are live,
// newest first, and there are min(L, frames) of them.
void expectRing(gpu::Context& ctx, const trajectory::Queue& queue,
                const std::vector<float>& frameTimes, uint64_t expectedOldest) {
    const auto live = queue.liveSegments();
    const uint64_t frames = frameTimes.size();
    ASSERT_EQ(live.size(), frames - expectedOldest);
    const std::vector<std::byte> ring = gpu::readBuffer(ctx, queue.vertices());
    for (size_t k = 0; k < live.size(); ++k) {
        const uint64_t frame = frames - 1 - k;
        EXPECT_EQ(live[k].frame, frame);
        EXPECT_EQ(live[k].birth, frameTimes[frame]);
        for (uint32_t i = 0; i < queue.verticesPerSegment(); ++i) {
            shared::TrajectoryVertex v;
            std::memcpy(&v,
                        ring.data() +
                            (size_t(live[k].firstVertex) + i) * sizeof(shared::TrajectoryVertex),
                        sizeof(v));
            ASSERT_EQ(v.velocity.w, frameTimes[frame]) << "slot of frame " << frame;
        }
    }
}

void runRing(gpu::Context& ctx, trajectory::Method method, uint32_t lifetime) {
    SCOPED_TRACE(std::string(trajectory::methodName(method)) + " L=" + std::to_string(lifetime));
    Source source = ringSource(5, 0.5f);
    trajectory::QueueOptions options;
    options.method = method;
    options.segment.subSamples = 3;
    options.lifetime = lifetime;
    options.maxLifetime = 64;
    auto queue = makeQueue(ctx, source, options);
    ASSERT_TRUE(queue);
    std::vector<float> times;
    for (int f = 0; f < 70; ++f) {
        const float t = 1.0f + 0.01f * float(f);
        times.push_back(t);
        gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
            queue->record(cmd, {rigid(glm::angleAxis(t, glm::vec3(0, 1, 0)), glm::vec3(t))}, t);
        });
        if (f < 3 || f % 7 == 0 || f >= 66)
            expectRing(ctx, *queue, times, times.size() - std::min<size_t>(times.size(), lifetime));
    }
}

TEST_F(TrajectoryGpu, RingWithLifetime1) {
    runRing(ctx(), trajectory::Method::Split, 1);
}
TEST_F(TrajectoryGpu, RingWithLifetime2) {
    runRing(ctx(), trajectory::Method::Split, 2);
}
TEST_F(TrajectoryGpu, RingWithLifetime64) {
    runRing(ctx(), trajectory::Method::Split, 64);
}
TEST_F(TrajectoryGpu, UnsplitTrailWithLifetime2And64) {
    runRing(ctx(), trajectory::Method::Unsplit, 2);
    runRing(ctx(), trajectory::Method::Unsplit, 64);
}

// L changes while running: a shrink drops the oldest segments at once, and they never come back;
// growing lets the trail lengthen one segment per frame.
TEST_F(TrajectoryGpu, LifetimeChangesWhileRunning) {
    for (trajectory::Method method : {trajectory::Method::Split, trajectory::Method::Unsplit}) {
        SCOPED_TRACE(trajectory::methodName(method));
        trajectory::QueueOptions options;
        options.method = method;
        options.lifetime = 8;
        options.maxLifetime = 16;
        auto queue = makeQueue(ctx(), ringSource(4, 0.5f), options);
        ASSERT_TRUE(queue);
        std::vector<float> times;
        auto frame = [&]() {
            const float t = 2.0f + 0.02f * float(times.size());
            times.push_back(t);
            gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
                queue->record(cmd, {rigid(glm::angleAxis(t, glm::vec3(1, 0, 0)), glm::vec3(0))}, t);
            });
        };
        for (int i = 0; i < 10; ++i)
            frame();
        expectRing(ctx(), *queue, times, 2); // frames 2..9
        ASSERT_TRUE(queue->setLifetime(3).ok());
        expectRing(ctx(), *queue, times, 7); // frames 7..9 at once
        frame();
        expectRing(ctx(), *queue, times, 8); // frames 8..10
        ASSERT_TRUE(queue->setLifetime(16).ok());
        expectRing(ctx(), *queue, times, 8); // nothing dropped comes back
        for (int i = 0; i < 3; ++i)
            frame();
        expectRing(ctx(), *queue, times, 8); // frames 8..13: grows one per frame
        for (int i = 0; i < 20; ++i)
            frame();
        expectRing(ctx(), *queue, times, times.size() - 16);
        EXPECT_FALSE(queue->setLifetime(0).ok());
        EXPECT_FALSE(queue->setLifetime(17).ok());
    }
}

// Split: one skinning per source vertex and S + 1 vertices per invocation whatever L is.
// Unsplit: skinning and vertices grow with L, but still S + 1 vertices per invocation (the
// segments are spread over invocations, not looped in one).
TEST_F(TrajectoryGpu, WritesPerInvocationDoNotDependOnLifetime) {
    const uint32_t s = 4;
    for (trajectory::Method method : {trajectory::Method::Split, trajectory::Method::Unsplit})
        for (uint32_t lifetime : {1u, 2u, 16u, 64u}) {
            trajectory::QueueOptions options;
            options.method = method;
            options.segment.subSamples = s;
            options.lifetime = lifetime;
            options.maxLifetime = 64;
            Source source = ringSource(7, 0.5f);
            auto queue = makeQueue(ctx(), source, options);
            ASSERT_TRUE(queue);
            gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
                for (uint32_t f = 0; f < lifetime + 2; ++f)
                    queue->record(cmd, {rigid(glm::quat(1, 0, 0, 0), glm::vec3(float(f)))},
                                  float(f) / 60.0f);
            });
            const trajectory::FrameStats& stats = queue->lastFrame();
            EXPECT_EQ(stats.verticesGenerated, stats.invocations * (s + 1));
            if (method == trajectory::Method::Split) {
                EXPECT_EQ(stats.invocations, 7u);
                EXPECT_EQ(stats.skinningEvaluations, 7u);
            } else {
                EXPECT_EQ(stats.invocations, 7u * lifetime);
                EXPECT_EQ(stats.skinningEvaluations, 2u * 7u * lifetime);
            }
            EXPECT_EQ(stats.liveSegments, lifetime);
        }
}

// Frames outside an effect's window write no segment: the trail ages out as usual, and the first
// segment after the gap starts afresh instead of reaching back across it.
TEST_F(TrajectoryGpu, SkippedFramesAgeOutAndTheTrailRestarts) {
    trajectory::QueueOptions options;
    options.lifetime = 4;
    options.maxLifetime = 4;
    options.segment.subSamples = 2;
    auto queue = makeQueue(ctx(), ringSource(3, 0.5f), options);
    ASSERT_TRUE(queue);
    auto frame = [&](int f, bool write) {
        const float t = 0.1f * float(f);
        if (!write) {
            queue->skip(t);
            return;
        }
        gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
            queue->record(cmd, {rigid(glm::quat(1, 0, 0, 0), glm::vec3(float(f), 0, 0))}, t);
        });
    };
    for (int f = 0; f < 3; ++f)
        frame(f, true);
    EXPECT_EQ(queue->liveSegments().size(), 3u);
    frame(3, false);
    frame(4, false);
    auto live = queue->liveSegments(); // frames 1 and 2 of 1..4
    ASSERT_EQ(live.size(), 2u);
    EXPECT_EQ(live[0].frame, 2u);
    EXPECT_EQ(queue->lastFrame().liveSegments, 2u);
    frame(5, true);
    live = queue->liveSegments(); // frames 2 and 5 of 2..5
    ASSERT_EQ(live.size(), 2u);
    EXPECT_EQ(live[0].frame, 5u);
    EXPECT_EQ(live[1].frame, 2u);
    const auto restarted = queue->readSegment(live[0]);
    for (const shared::TrajectoryVertex& v : restarted) {
        EXPECT_EQ(glm::vec3(v.velocity),
                  glm::vec3(0.0f)); // no extent: not reaching back to frame 2
        EXPECT_EQ(v.velocity.w, 0.5f);
    }
    frame(6, true);
    const auto next = queue->readSegment(queue->liveSegments()[0]);
    EXPECT_NEAR(next[0].velocity.x, 1.0f / 0.1f, 1e-3f); // one unit per 0.1 s
    for (int f = 7; f < 11; ++f)
        frame(f, false);
    EXPECT_TRUE(queue->liveSegments().empty());
}

// The baseline rebuilds the same trail the split method keeps.
TEST_F(TrajectoryGpu, UnsplitTrailEqualsTheSplitOne) {
    const anim::Character fighter = anim::makeFighter();
    trajectory::Selection selection;
    selection.meshes = {"sword"};
    Source source = trajectory::selectSource(fighter, selection).value();
    const anim::Clip& slash = *fighter.findClip("sword_slash");
    trajectory::QueueOptions options;
    options.lifetime = 6;
    options.maxLifetime = 8;
    options.segment.subSamples = 4;
    auto split = makeQueue(ctx(), source, options);
    options.method = trajectory::Method::Unsplit;
    auto unsplit = makeQueue(ctx(), source, options);
    ASSERT_TRUE(split && unsplit);
    gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
        for (int f = 0; f < 10; ++f) {
            const float t = 0.2f + float(f) / 60.0f;
            const auto palette = fighterPalette(fighter, source, slash, t);
            split->record(cmd, palette, t);
            unsplit->record(cmd, palette, t);
        }
    });
    const auto a = split->liveSegments(), b = unsplit->liveSegments();
    ASSERT_EQ(a.size(), 6u);
    ASSERT_EQ(b.size(), 6u);
    double worst = 0.0;
    for (size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].frame, b[k].frame);
        const auto sa = split->readSegment(a[k]), sb = unsplit->readSegment(b[k]);
        for (size_t i = 0; i < sa.size(); ++i) {
            worst = std::max(
                worst, double(glm::length(glm::vec3(sa[i].position) - glm::vec3(sb[i].position))));
            ASSERT_EQ(sa[i].velocity.w, sb[i].velocity.w);
        }
    }
    EXPECT_LE(worst, 1e-6);
}

// The paper's way (a geometry shader into transform feedback) writes the same segments as the
// compute pass, and its ends weld too.
TEST_F(TrajectoryGpu, StreamOutputWritesTheSameSegments) {
    if (!ctx().features().geometryShader || !ctx().features().transformFeedback)
        GTEST_SKIP() << ctx().info().name << " has no geometry shaders or transform feedback";
    const anim::Character fighter = anim::makeFighter();
    trajectory::Selection selection;
    selection.bones = {"shin_r", "foot_r", "toe_r"};
    Source source = trajectory::selectSource(fighter, selection).value();
    const anim::Clip& kick = *fighter.findClip("roundhouse_kick");
    trajectory::QueueOptions options;
    options.lifetime = 5;
    options.maxLifetime = 5;
    options.segment.subSamples = 16; // the most a geometry invocation emits here
    auto compute = makeQueue(ctx(), source, options);
    options.method = trajectory::Method::StreamOutput;
    auto xfb = makeQueue(ctx(), source, options);
    ASSERT_TRUE(compute && xfb);
    gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
        for (int f = 0; f < 7; ++f) {
            const float t = 0.3f + float(f) / 60.0f;
            const auto palette = fighterPalette(fighter, source, kick, t);
            compute->record(cmd, palette, t);
            xfb->record(cmd, palette, t);
        }
    });
    const auto a = compute->liveSegments(), b = xfb->liveSegments();
    ASSERT_EQ(a.size(), 5u);
    ASSERT_EQ(b.size(), 5u);
    double worst = 0.0;
    std::vector<std::vector<shared::TrajectoryVertex>> segments;
    for (size_t k = 0; k < a.size(); ++k) {
        const auto sa = compute->readSegment(a[k]);
        segments.push_back(xfb->readSegment(b[k]));
        const auto& sb = segments.back();
        for (size_t i = 0; i < sa.size(); ++i) {
            worst = std::max(
                worst, double(glm::length(glm::vec3(sa[i].position) - glm::vec3(sb[i].position))));
            ASSERT_EQ(sa[i].velocity.w, sb[i].velocity.w) << "segment " << k << " vertex " << i;
        }
    }
    EXPECT_LE(worst, 1e-6);
    const uint32_t per = options.segment.subSamples + 1;
    for (size_t k = 0; k + 1 < segments.size(); ++k)
        for (size_t v = 0; v < source.vertices.size(); ++v)
            ASSERT_EQ(std::memcmp(&segments[k][v * per + per - 1].position,
                                  &segments[k + 1][v * per].position, 12),
                      0)
                << "weld between segments " << k << " and " << k + 1 << ", vertex " << v;
}

TEST_F(TrajectoryGpu, IndexBuffersConnectTheSamples) {
    Source source = ringSource(6, 0.5f); // 4 triangles
    trajectory::QueueOptions options;
    options.segment.subSamples = 5;
    options.maxLifetime = 4;
    options.lifetime = 4;
    options.kind = trajectory::Kind::Lines;
    auto lines = makeQueue(ctx(), source, options);
    options.kind = trajectory::Kind::Volumes;
    auto volumes = makeQueue(ctx(), source, options);
    options.kind = trajectory::Kind::Particles;
    auto particles = makeQueue(ctx(), source, options);
    ASSERT_TRUE(lines && volumes && particles);
    EXPECT_EQ(lines->indicesPerSegment(), 6u * 5u * 2u);
    EXPECT_EQ(volumes->indicesPerSegment(), 4u * 3u * 5u * 6u);
    EXPECT_EQ(particles->indicesPerSegment(), 0u);
    const auto indices = gpu::readBufferAs<uint32_t>(ctx(), volumes->indices());
    for (uint32_t i : indices)
        ASSERT_LT(i, volumes->verticesPerSegment());
}

TEST_F(TrajectoryGpu, BadOptionsAreRefused) {
    trajectory::QueueOptions options;
    options.lifetime = 65;
    options.maxLifetime = 64;
    auto tooLong = trajectory::Queue::create(ctx(), ringSource(3, 1.0f), options);
    ASSERT_FALSE(tooLong.ok());
    EXPECT_NE(tooLong.error().message.find("lifetime 65"), std::string::npos);
    options = {};
    options.segment.subSamples = 0;
    EXPECT_FALSE(trajectory::Queue::create(ctx(), ringSource(3, 1.0f), options).ok());
    options = {};
    options.kind = trajectory::Kind::Volumes;
    Source noTriangles = ringSource(3, 1.0f);
    noTriangles.triangles.clear();
    EXPECT_FALSE(trajectory::Queue::create(ctx(), noTriangles, options).ok());
}

} // namespace
} // namespace mfx::test
