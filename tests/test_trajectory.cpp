// Trajectory segments on the CPU: the geometry of a segment (static, translation, the arc of a
// rotation) and the selection of source vertices. The GPU queue: test_trajectory_queue.cpp.
#include "core/anim/fighter.h"
#include "core/trajectory/build_segment.h"
#include "core/trajectory/trajectory_source.h"
#include "tests/trajectory_test_util.h"

#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

namespace mfx::test {
namespace {

using trajectory::SegmentParameters;
using trajectory::Source;

std::vector<shared::TrajectoryVertex> cpuSegment(const Source& source,
                                                 const anim::DualQuatJoint& now,
                                                 const anim::DualQuatJoint& previous, float time,
                                                 float dt, const SegmentParameters& parameters) {
    return trajectory::buildSegment(source, trajectory::vertexTransforms(source, {now}),
                                    trajectory::vertexTransforms(source, {previous}), time, dt,
                                    parameters);
}

// --- The geometry of one segment (CPU twin)
// --------------------------------------------------------

TEST(TrajectorySegment, StaticPoseHasZeroExtent) {
    const Source source = ringSource(12, 0.7f);
    SegmentParameters parameters;
    parameters.subSamples = 8;
    const anim::DualQuatJoint pose = rigid(glm::angleAxis(0.4f, glm::vec3(0, 1, 0)), {1, 2, 3});
    const auto segment = cpuSegment(source, pose, pose, 1.0f, 1.0f / 60.0f, parameters);
    ASSERT_EQ(segment.size(), 12u * 9u);
    for (size_t v = 0; v < 12; ++v)
        for (size_t i = 0; i <= 8; ++i) {
            const shared::TrajectoryVertex& s = segment[v * 9 + i];
            EXPECT_EQ(glm::vec3(s.position), glm::vec3(segment[v * 9].position)) << v << "," << i;
            EXPECT_EQ(glm::vec3(s.velocity), glm::vec3(0.0f)) << v << "," << i;
        }
}

TEST(TrajectorySegment, PureTranslationIsStraightAndEvenlySpaced) {
    const Source source = ringSource(12, 0.7f);
    SegmentParameters parameters;
    parameters.subSamples = 8;
    const glm::quat r = glm::angleAxis(0.4f, glm::vec3(0, 1, 0));
    const glm::vec3 move(0.3f, -0.1f, 0.2f);
    const float dt = 1.0f / 60.0f;
    const auto segment =
        cpuSegment(source, rigid(r, move), rigid(r, glm::vec3(0.0f)), 1.0f, dt, parameters);
    for (size_t v = 0; v < 12; ++v) {
        const glm::vec3 start(segment[v * 9].position);
        for (size_t i = 0; i <= 8; ++i) {
            const glm::vec3 expected = start - move * (float(i) / 8.0f);
            EXPECT_LE(glm::length(glm::vec3(segment[v * 9 + i].position) - expected), 1e-6f)
                << v << "," << i;
            // The velocity of a straight, uniform move: move / dt everywhere.
            EXPECT_LE(glm::length(glm::vec3(segment[v * 9 + i].velocity) - move / dt),
                      1e-3f * glm::length(move / dt))
                << v << "," << i;
        }
    }
}

// A rigid rotation of 90 degrees about y between two frames: the sub-samples lie on the circle
// the vertex really travels; interpolating the end positions linearly cuts the chord instead.
TEST(TrajectorySegment, RotationFollowsTheArcWhereLinearInterpolationCutsTheChord) {
    const float radius = 0.8f;
    const Source source = ringSource(16, radius);
    SegmentParameters parameters;
    parameters.subSamples = 16;
    const glm::vec3 up(0, 1, 0);
    const auto now = rigid(glm::angleAxis(glm::radians(90.0f), up), glm::vec3(0.0f));
    const auto previous = rigid(glm::quat(1, 0, 0, 0), glm::vec3(0.0f));
    const auto segment = cpuSegment(source, now, previous, 1.0f, 1.0f / 30.0f, parameters);
    double worstArc = 0.0, worstLinear = 0.0;
    for (size_t v = 0; v < 16; ++v) {
        const glm::vec3 a(segment[v * 17].position), b(segment[v * 17 + 16].position);
        for (size_t i = 0; i <= 16; ++i) {
            const glm::vec3 p(segment[v * 17 + i].position);
            const double radial = std::abs(glm::length(glm::vec2(p.x, p.z)) - radius);
            worstArc = std::max(worstArc, radial);
            const float tau = float(i) / 16.0f;
            const glm::vec3 lerped = (1.0f - tau) * a + tau * b;
            worstLinear = std::max(
                worstLinear, double(std::abs(glm::length(glm::vec2(lerped.x, lerped.z)) - radius)));
            EXPECT_NEAR(p.y, a.y, 1e-6f); // stays in its plane
        }
    }
    std::printf("90-degree turn, radius %.2f: dual quaternion sub-samples %.3g off the arc, linear "
                "interpolation %.3g (%.0fx worse)\n",
                double(radius), worstArc, worstLinear, worstLinear / std::max(worstArc, 1e-12));
    EXPECT_LT(worstArc, 1e-4 * double(radius));
    // The chord's midpoint is r cos(45 degrees) from the centre: 29% of the radius off.
    EXPECT_GT(worstLinear, 0.25 * double(radius));
    EXPECT_GT(worstLinear, 1000.0 * worstArc);
}

TEST(TrajectorySegment, AttenuationRunsFromStartToEnd) {
    SegmentParameters p;
    p.alphaStart = 0.9f;
    p.alphaEnd = 0.1f;
    p.alphaPower = 2.0f;
    EXPECT_FLOAT_EQ(trajectory::attenuation(0.0f, p), 0.9f);
    EXPECT_FLOAT_EQ(trajectory::attenuation(1.0f, p), 0.1f);
    EXPECT_FLOAT_EQ(trajectory::attenuation(0.5f, p), 0.9f - 0.8f * 0.25f);
}

TEST(TrajectorySegment, BadParametersAreRefusedByName) {
    SegmentParameters p;
    p.subSamples = 17;
    EXPECT_NE(trajectory::checkParameters(p).error().message.find("sub_samples 17"),
              std::string::npos);
    p = {};
    p.subSamples = 0;
    EXPECT_FALSE(trajectory::checkParameters(p).ok());
    p = {};
    p.impulseScale = std::nanf("");
    EXPECT_FALSE(trajectory::checkParameters(p).ok());
    p = {};
    p.alphaPower = 0.0f;
    EXPECT_FALSE(trajectory::checkParameters(p).ok());
    p = {};
    p.alphaEnd = 1.5f;
    EXPECT_FALSE(trajectory::checkParameters(p).ok());
}

// --- Choosing the source vertices ----------------------------------------------------------------

TEST(TrajectorySource, WholeFighterByDefault) {
    const anim::Character fighter = anim::makeFighter();
    const auto selected = trajectory::selectSource(fighter, {});
    ASSERT_TRUE(selected.ok()) << selected.error().message;
    size_t vertices = 0, indices = 0;
    for (const anim::Mesh& m : fighter.meshes)
        for (const anim::Primitive& p : m.primitives) {
            vertices += p.positions.size();
            indices += p.indices.size();
        }
    EXPECT_EQ(selected.value().vertices.size(), vertices);
    EXPECT_EQ(selected.value().triangles.size(), indices);
    EXPECT_EQ(selected.value().palette.size(), fighter.skins[0].joints.size());
}

TEST(TrajectorySource, BonesKeepOnlyTheirVertices) {
    const anim::Character fighter = anim::makeFighter();
    trajectory::Selection selection;
    selection.meshes = {"body"};
    selection.bones = {"foot_r", "toe_r"};
    const auto selected = trajectory::selectSource(fighter, selection);
    ASSERT_TRUE(selected.ok()) << selected.error().message;
    const Source& s = selected.value();
    EXPECT_GT(s.vertices.size(), 20u);
    EXPECT_LT(s.vertices.size(), 1000u);
    for (uint32_t index : s.triangles)
        ASSERT_LT(index, s.vertices.size());
    // Every kept vertex is weighted at least half to the right foot or toe.
    const int foot = *fighter.findNode("foot_r"), toe = *fighter.findNode("toe_r");
    for (const shared::SkinVertexIn& v : s.vertices) {
        float w = 0.0f;
        for (int k = 0; k < 4; ++k) {
            const trajectory::PaletteEntry& e = s.palette[v.joints[k]];
            const int node = fighter.skins[size_t(e.skin)].joints[size_t(e.joint)];
            if (node == foot || node == toe) w += v.weights[k];
        }
        ASSERT_GE(w, 0.5f);
    }
}

TEST(TrajectorySource, UnknownNamesAreListed) {
    const anim::Character fighter = anim::makeFighter();
    trajectory::Selection selection;
    selection.bones = {"hand_r", "hand_X"};
    const auto bone = trajectory::selectSource(fighter, selection);
    ASSERT_FALSE(bone.ok());
    EXPECT_NE(bone.error().message.find("bones[1]: no bone \"hand_X\"; bones are: hips, "),
              std::string::npos)
        << bone.error().message;
    selection = {};
    selection.meshes = {"cape"};
    const auto mesh = trajectory::selectSource(fighter, selection);
    ASSERT_FALSE(mesh.ok());
    EXPECT_NE(mesh.error().message.find("meshes[0]: no mesh \"cape\"; meshes are: body, sword"),
              std::string::npos)
        << mesh.error().message;
}

} // namespace
} // namespace mfx::test
