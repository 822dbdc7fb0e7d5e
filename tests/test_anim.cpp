// Animation: channel sampling against hand-computed values (LINEAR, STEP, CUBICSPLINE, before
// the first and after the last key), clip time wrapping, poses, and the character invariants.
#include "core/anim/character.h"
#include "core/anim/fighter.h"
#include "core/anim/sampling.h"

#include <cmath>
#include <gtest/gtest.h>

namespace mfx::test {
namespace {

using anim::Channel;
using anim::Interpolation;
using anim::Path;

constexpr float kEps = 1e-6f;

void expectNear(const glm::vec4& a, const glm::vec4& b, float eps = kEps) {
    for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(a[i], b[i], eps) << "component " << i;
}

Channel channel(Path path, Interpolation interpolation, std::vector<float> times,
                std::vector<glm::vec4> values) {
    Channel c;
    c.path = path;
    c.interpolation = interpolation;
    c.times = std::move(times);
    c.values = std::move(values);
    return c;
}

TEST(AnimSampling, LinearTranslationBetweenBeforeAndAfterKeys) {
    const Channel c = channel(Path::Translation, Interpolation::Linear, {1.0f, 3.0f},
                              {{0, 0, 0, 0}, {4, 2, -2, 0}});
    expectNear(anim::sampleChannel(c, 0.0f), {0, 0, 0, 0}); // before the first key
    expectNear(anim::sampleChannel(c, 1.0f), {0, 0, 0, 0});
    expectNear(anim::sampleChannel(c, 1.5f), {1, 0.5f, -0.5f, 0});
    expectNear(anim::sampleChannel(c, 2.0f), {2, 1, -1, 0});
    expectNear(anim::sampleChannel(c, 3.0f), {4, 2, -2, 0});
    expectNear(anim::sampleChannel(c, 10.0f), {4, 2, -2, 0}); // after the last key
}

TEST(AnimSampling, LinearRotationIsSlerpTheShortWay) {
    const float h = std::sqrt(0.5f);
    // Identity to 90 degrees about z, the second key stored as its negative (the same rotation).
    const Channel c = channel(Path::Rotation, Interpolation::Linear, {0.0f, 1.0f},
                              {{0, 0, 0, 1}, {0, 0, -h, -h}});
    const float half = std::acos(-1.0f) / 8.0f; // 45 degrees: half-angle 22.5
    const glm::vec4 q = anim::sampleChannel(c, 0.5f);
    expectNear(q * (q.w < 0.0f ? -1.0f : 1.0f), {0, 0, std::sin(half), std::cos(half)});
    // A quarter of the way: 22.5 degrees, which a normalised lerp would not give exactly.
    const glm::vec4 r = anim::sampleChannel(c, 0.25f);
    const float quarter = std::acos(-1.0f) / 16.0f;
    expectNear(r * (r.w < 0.0f ? -1.0f : 1.0f), {0, 0, std::sin(quarter), std::cos(quarter)});
}

TEST(AnimSampling, StepHoldsThePreviousKey) {
    const Channel c = channel(Path::Scale, Interpolation::Step, {0.0f, 1.0f, 2.0f},
                              {{1, 1, 1, 0}, {2, 2, 2, 0}, {3, 3, 3, 0}});
    expectNear(anim::sampleChannel(c, -1.0f), {1, 1, 1, 0});
    expectNear(anim::sampleChannel(c, 0.99f), {1, 1, 1, 0});
    expectNear(anim::sampleChannel(c, 1.0f), {2, 2, 2, 0});
    expectNear(anim::sampleChannel(c, 1.5f), {2, 2, 2, 0});
    expectNear(anim::sampleChannel(c, 2.0f), {3, 3, 3, 0});
    expectNear(anim::sampleChannel(c, 7.0f), {3, 3, 3, 0});
}

TEST(AnimSampling, CubicSplineIsHermiteWithScaledTangents) {
    // Keys at 0 and 2: values 1 and 3 (x), out-tangent of key 0 is 2 per second, in-tangent of
    // key 1 is 0. At t = 1 (u = 1/2, interval 2): h00 = 1/2, h10 = 1/8, h01 = 1/2, h11 = -1/8,
    // p = 1/2 * 1 + 1/8 * (2 * 2) + 1/2 * 3 - 1/8 * 0 = 2.5.
    const Channel c = channel(Path::Translation, Interpolation::CubicSpline, {0.0f, 2.0f},
                              {{9, 9, 9, 0},
                               {1, 0, 0, 0},
                               {2, 0, 0, 0}, // key 0
                               {0, 0, 0, 0},
                               {3, 0, 0, 0},
                               {9, 9, 9, 0}}); // key 1
    expectNear(anim::sampleChannel(c, 1.0f), {2.5f, 0, 0, 0});
    // u = 1/4: h00 = 27/32, h10 = 9/64, h01 = 5/32, h11 = -3/64 -> 27/32 + 9/16 + 15/32 = 1.875.
    expectNear(anim::sampleChannel(c, 0.5f), {1.875f, 0, 0, 0});
    // Outside the keys: the values, never the tangents.
    expectNear(anim::sampleChannel(c, -1.0f), {1, 0, 0, 0});
    expectNear(anim::sampleChannel(c, 5.0f), {3, 0, 0, 0});
}

TEST(AnimSampling, CubicSplineRotationIsNormalised) {
    const Channel c = channel(
        Path::Rotation, Interpolation::CubicSpline, {0.0f, 1.0f},
        {{0, 0, 0, 0}, {0, 0, 0, 1}, {0, 0, 1, 0}, {0, 0, 1, 0}, {0, 0, 1, 0}, {0, 0, 0, 0}});
    EXPECT_NEAR(glm::length(anim::sampleChannel(c, 0.5f)), 1.0f, kEps);
}

TEST(AnimSampling, ClipTimeLoopsOrClamps) {
    anim::Clip clip;
    clip.duration = 2.0f;
    EXPECT_NEAR(anim::clipTime(clip, 5.0f, anim::Wrap::Loop), 1.0f, kEps);
    EXPECT_NEAR(anim::clipTime(clip, -0.5f, anim::Wrap::Loop), 1.5f, kEps);
    EXPECT_NEAR(anim::clipTime(clip, 5.0f, anim::Wrap::Clamp), 2.0f, kEps);
    EXPECT_NEAR(anim::clipTime(clip, -3.0f, anim::Wrap::Clamp), 0.0f, kEps);
    EXPECT_EQ(anim::clipTime(clip, NAN, anim::Wrap::Loop), 0.0f);
}

anim::Character twoNodeCharacter() {
    anim::Character c;
    c.nodes.push_back({"root", -1, {}});
    c.nodes.push_back({"child", 0, {}});
    c.nodes[0].rest.translation = {1, 0, 0};
    c.nodes[1].rest.translation = {0, 2, 0};
    anim::Clip clip;
    clip.name = "turn";
    clip.duration = 1.0f;
    const float h = std::sqrt(0.5f);
    clip.channels.push_back(
        channel(Path::Rotation, Interpolation::Linear, {0.0f, 1.0f}, {{0, 0, 0, 1}, {0, 0, h, h}}));
    clip.channels.back().node = 0;
    c.clips.push_back(clip);
    return c;
}

TEST(AnimPose, WorldIsParentTimesLocal) {
    const anim::Character c = twoNodeCharacter();
    ASSERT_TRUE(anim::checkInvariants(c).ok());
    const anim::Pose rest = anim::samplePose(c, nullptr, 0.0f);
    EXPECT_NEAR(rest.world[1][3].x, 1.0f, kEps);
    EXPECT_NEAR(rest.world[1][3].y, 2.0f, kEps);
    // At the end of the clip the root has turned 90 degrees about z: the child's offset (0, 2, 0)
    // now points along -x.
    const anim::Pose end = anim::samplePose(c, &c.clips[0], 1.0f, anim::Wrap::Clamp);
    EXPECT_NEAR(end.world[1][3].x, -1.0f, 1e-5f);
    EXPECT_NEAR(end.world[1][3].y, 0.0f, 1e-5f);
}

// A host's pose comes as world matrices alone: the locals recovered from them give the same
// world matrices again, for every node of the fighter in the middle of its kick.
TEST(AnimPose, FromWorldMatricesTheLocalsRebuildThem) {
    const anim::Character fighter = anim::makeFighter();
    const anim::Pose sampled = anim::samplePose(fighter, &fighter.clips[0], 0.4f);
    const anim::Pose given = anim::poseFromWorld(fighter, sampled.world);
    ASSERT_EQ(given.local.size(), sampled.local.size());
    const anim::Pose rebuilt = anim::interpolatePose(fighter, given, given, 0.5f);
    for (size_t n = 0; n < sampled.world.size(); ++n)
        for (int c = 0; c < 4; ++c)
            expectNear(rebuilt.world[n][c], sampled.world[n][c], 1e-5f);
}

// Half way between two poses: the root at the middle of its path, and the child swung on an arc
// about its parent (the offset keeps its length 2, where a blend of the world matrices would
// shorten it to 2 cos 45 degrees).
TEST(AnimPose, InterpolatedPosesSwingLimbsOnArcs) {
    const anim::Character c = twoNodeCharacter();
    const anim::Pose start = anim::samplePose(c, &c.clips[0], 0.0f, anim::Wrap::Clamp);
    const anim::Pose end = anim::samplePose(c, &c.clips[0], 1.0f, anim::Wrap::Clamp);
    const anim::Pose half = anim::interpolatePose(c, anim::poseFromWorld(c, start.world),
                                                  anim::poseFromWorld(c, end.world), 0.5f);
    const glm::vec3 offset = glm::vec3(half.world[1][3]) - glm::vec3(half.world[0][3]);
    EXPECT_NEAR(glm::length(offset), 2.0f, 1e-5f);
    const anim::Pose sampledHalf = anim::samplePose(c, &c.clips[0], 0.5f, anim::Wrap::Clamp);
    for (int col = 0; col < 4; ++col)
        expectNear(half.world[1][col], sampledHalf.world[1][col], 1e-5f);
}

TEST(AnimCharacter, InvariantsNameTheBadElement) {
    anim::Character c = twoNodeCharacter();
    c.skins.push_back({"skin", {0, 1}, {glm::mat4(1.0f)}});
    const Status bad = anim::checkInvariants(c);
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().message, "skins[0]: 1 inverse bind matrices for 2 joints");

    c = twoNodeCharacter();
    c.clips[0].channels[0].times = {0.0f, 0.0f};
    const Status times = anim::checkInvariants(c);
    ASSERT_FALSE(times.ok());
    EXPECT_NE(times.error().message.find("clips[0].channels[0]"), std::string::npos);

    c = twoNodeCharacter();
    c.nodes[0].parent = 1;
    EXPECT_FALSE(anim::checkInvariants(c).ok());
}

} // namespace
} // namespace mfx::test
