// Hits between moving capsules (core/anim/capsule_contact.h): the closest points of two segments,
// and the first contact of a blow within a frame at its analytic time and point; a blow that
// misses, and capsules that touch already when the frame starts, give none.
#include "core/anim/capsule_contact.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mfx::test {
namespace {

using anim::PosedCapsule;
using anim::SweptCapsule;

TEST(SegmentPoints, ClosestPointsOfCrossingParallelAndEndToEndSegments) {
    // Crossing at right angles, 1 apart along z: the crossing point and the one above it.
    anim::SegmentPoints p = anim::closestPoints({-1, 0, 0}, {1, 0, 0}, {0.5f, -1, 1}, {0.5f, 1, 1});
    EXPECT_NEAR(p.s, 0.75f, 1e-6f);
    EXPECT_NEAR(p.t, 0.5f, 1e-6f);
    EXPECT_NEAR(glm::distance(p.p, glm::vec3(0.5f, 0, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(p.q, glm::vec3(0.5f, 0, 1)), 0.0f, 1e-6f);
    // End to end on one line: the facing ends.
    p = anim::closestPoints({0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {2, 0, 0});
    EXPECT_NEAR(glm::distance(p.p, p.q), 1.0f, 1e-6f);
    // Parallel, overlapping: the distance between the lines.
    p = anim::closestPoints({0, 0, 0}, {2, 0, 0}, {1, 0.5f, 0}, {3, 0.5f, 0});
    EXPECT_NEAR(glm::distance(p.p, p.q), 0.5f, 1e-6f);
    // A point against a segment.
    p = anim::closestPoints({1, 2, 0}, {1, 2, 0}, {0, 0, 0}, {4, 0, 0});
    EXPECT_NEAR(glm::distance(p.q, glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
}

// A fist (a vertical capsule of radius 0.1 from y = 0 to 1) swept along +x from x = -1 to 1 over
// one frame of 1/30 s, against a target lying along z at x = 0.5, y = 0.5 (radius 0.2). They
// touch when the fist's axis is 0.3 from the target's: x = 0.2, at a time of (0.2 + 1) / 2 = 0.6
// of the frame, the fist's surface at (0.3, 0.5, 0), moving +x at 60 m/s.
SweptCapsule fist(float y0, float from, float to) {
    return {{{from, y0, 0}, {from, y0 + 1, 0}, 0.1f}, {{to, y0, 0}, {to, y0 + 1, 0}, 0.1f}};
}
const SweptCapsule kTarget = {{{0.5f, 0.5f, -1}, {0.5f, 0.5f, 1}, 0.2f},
                              {{0.5f, 0.5f, -1}, {0.5f, 0.5f, 1}, 0.2f}};

TEST(CapsuleContact, ABlowHitsAtTheAnalyticTimeAndPoint) {
    const auto hit = anim::firstContact(fist(0.0f, -1.0f, 1.0f), kTarget, 1.0f / 30.0f);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->time, 0.6f, 1e-5f);
    EXPECT_NEAR(glm::distance(hit->point, glm::vec3(0.3f, 0.5f, 0.0f)), 0.0f, 1e-4f);
    EXPECT_NEAR(hit->speed, 60.0f, 1e-3f);
    EXPECT_NEAR(glm::distance(hit->direction, glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
}

// So fast that it would pass through the target between two even samples of the frame (3 m in
// a frame against an overlap 0.6 wide): the sub-steps follow the travel, and it still hits.
TEST(CapsuleContact, AFastBlowDoesNotTunnelThrough) {
    const auto hit = anim::firstContact(fist(0.0f, -1.0f, 2.0f), kTarget, 1.0f / 30.0f);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->time, 1.2f / 3.0f, 1e-5f);
}

TEST(CapsuleContact, ABlowThatMissesOrTouchesAlreadyGivesNone) {
    // Passing above: the fist's bottom at y = 0.81, 0.01 clear of the target's top at 0.7 + 0.1.
    EXPECT_FALSE(anim::firstContact(fist(0.81f, -1.0f, 1.0f), kTarget, 1.0f / 30.0f));
    // Stopping short: its surface ends at x = 0.29, 0.01 from the target's.
    EXPECT_FALSE(anim::firstContact(fist(0.0f, -1.0f, 0.19f), kTarget, 1.0f / 30.0f));
    // Touching when the frame starts: the contact began before this frame.
    EXPECT_FALSE(anim::firstContact(fist(0.0f, 0.25f, 0.6f), kTarget, 1.0f / 30.0f));
}

// The time is found within a millionth of the frame over many approaches (the analytic time of
// a fist approaching from a random start at a random speed).
TEST(CapsuleContact, TheTimeIsAnalyticOverManyBlows) {
    for (int i = 0; i < 200; ++i) {
        const float from = -3.0f + 0.01f * float(i), to = 0.25f + 0.02f * float(i % 50);
        const auto hit = anim::firstContact(fist(0.0f, from, to), kTarget, 1.0f / 60.0f);
        ASSERT_TRUE(hit) << i;
        EXPECT_NEAR(hit->time, (0.2f - from) / (to - from), 2e-6f) << i;
    }
}

} // namespace
} // namespace mfx::test
