// Skinning on the CPU: dual quaternion skinning equals linear blend skinning for a vertex bound to
// one joint, and keeps the cross-section of a twisted two-joint cylinder where linear blending
// collapses it.
#include "core/anim/skinning.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace mfx::test {
namespace {

const float kPi = std::acos(-1.0f);

glm::mat4 trs(glm::vec3 t, float angle, glm::vec3 axis, glm::vec3 s) {
    return glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), t), angle, axis), s);
}

TEST(SkinningDualQuat, DecomposeRebuildsTheMatrix) {
    const glm::mat4 m = trs({1, -2, 3}, 0.7f, glm::normalize(glm::vec3(1, 2, 3)), {2, 0.5f, 1.5f});
    const math::Decomposed d = math::decompose(m);
    const glm::mat4 back = glm::scale(
        glm::translate(glm::mat4(1.0f), d.translation) * glm::mat4_cast(d.rotation), d.scale);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(back[c][r], m[c][r], 1e-5f) << c << "," << r;
}

TEST(SkinningDualQuat, OneJointEqualsLinearBlend) {
    const std::vector<glm::mat4> matrices = {
        trs({0.3f, 1.0f, -2.0f}, 1.1f, glm::normalize(glm::vec3(0, 1, 1)), {1.0f, 1.0f, 1.0f}),
        trs({-1.0f, 0.5f, 0.25f}, 2.5f, glm::normalize(glm::vec3(1, -1, 0.5f)), {2.0f, 2.0f, 2.0f}),
        trs({4.0f, -3.0f, 1.0f}, -0.8f, glm::vec3(0, 0, 1), {1.5f, 0.5f, 2.0f}), // non-uniform
    };
    const std::vector<anim::DualQuatJoint> palette = anim::dualQuatPalette(matrices);
    const glm::vec3 p(0.4f, -1.2f, 2.2f);
    const glm::vec3 n = glm::normalize(glm::vec3(1.0f, 2.0f, -0.5f));
    for (uint32_t j = 0; j < 3; ++j) {
        // The joint in any slot, the other weights 0.
        const glm::uvec4 joints(2 - j, j, (j + 1) % 3, 0);
        const glm::vec4 weights(0.0f, 1.0f, 0.0f, 0.0f);
        const anim::SkinnedVertex dq = anim::skinDualQuat(palette, p, n, joints, weights);
        const anim::SkinnedVertex lbs = anim::skinLinear(matrices, p, n, joints, weights);
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(dq.position[a], lbs.position[a], 1e-5f) << "joint " << j;
            EXPECT_NEAR(dq.normal[a], lbs.normal[a], 1e-5f) << "joint " << j;
        }
    }
}

// A cylinder of radius 1 along x from 0 to 2, bound to joint 0 (at x = 0) and joint 1 (at x = 1):
// the weight of joint 1 rises linearly from 0 at x = 0.5 to 1 at x = 1.5. Joint 1 twists 90
// degrees about x. Returns the area of the skinned cross-section ring at `x`, over pi.
double twistedRingArea(float x, anim::SkinningMethod method) {
    const glm::mat4 inverseBind1 = glm::translate(glm::mat4(1.0f), glm::vec3(-1, 0, 0));
    const glm::mat4 world1 = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0)),
                                         kPi / 2.0f, glm::vec3(1, 0, 0));
    const std::vector<glm::mat4> matrices = {glm::mat4(1.0f), world1 * inverseBind1};
    const std::vector<anim::DualQuatJoint> palette = anim::dualQuatPalette(matrices);
    const float w1 = std::clamp(x - 0.5f, 0.0f, 1.0f);
    const int ring = 64;
    std::vector<glm::dvec3> points;
    for (int i = 0; i < ring; ++i) {
        const float a = 2.0f * kPi * float(i) / float(ring);
        const glm::vec3 p(x, std::cos(a), std::sin(a));
        const glm::vec3 n(0.0f, std::cos(a), std::sin(a));
        const glm::uvec4 joints(0, 1, 0, 0);
        const glm::vec4 weights(1.0f - w1, w1, 0.0f, 0.0f);
        const anim::SkinnedVertex v = method == anim::SkinningMethod::DualQuat
                                          ? anim::skinDualQuat(palette, p, n, joints, weights)
                                          : anim::skinLinear(matrices, p, n, joints, weights);
        points.push_back(glm::dvec3(v.position));
    }
    // Area of the (planar, x = const for a twist about x) polygon: half the cross products' sum.
    glm::dvec3 sum(0.0);
    for (int i = 0; i < ring; ++i)
        sum += glm::cross(points[size_t(i)], points[size_t((i + 1) % ring)]);
    const double polygonOfUnitCircle = 0.5 * ring * std::sin(2.0 * std::acos(-1.0) / ring);
    return 0.5 * glm::length(sum) / polygonOfUnitCircle;
}

TEST(SkinningDualQuat, TwistKeepsTheCrossSectionWhereLinearBlendLosesIt) {
    // Where both joints weigh 1/2 (x = 1) the twist is 45 degrees: linear blending averages
    // points 90 degrees apart (radius cos 45, half the area); dual quaternions rotate them.
    const double dq = twistedRingArea(1.0f, anim::SkinningMethod::DualQuat);
    const double lbs = twistedRingArea(1.0f, anim::SkinningMethod::Linear);
    RecordProperty("dualQuatArea", std::to_string(dq));
    RecordProperty("linearArea", std::to_string(lbs));
    EXPECT_NEAR(dq, 1.0, 0.05);
    EXPECT_LT(lbs, 0.75);
    EXPECT_NEAR(lbs, 0.5, 1e-3); // the analytic value
    // Every ring along the blend region, not only the middle.
    for (float x : {0.6f, 0.8f, 1.2f, 1.4f})
        EXPECT_NEAR(twistedRingArea(x, anim::SkinningMethod::DualQuat), 1.0, 0.05) << x;
}

TEST(SkinningDualQuat, SignRuleTakesTheShortWay) {
    // The same rotation stored with opposite signs in two joints must blend to itself.
    const glm::quat q = glm::angleAxis(2.0f, glm::normalize(glm::vec3(1, 1, 0)));
    std::vector<anim::DualQuatJoint> palette = {
        {math::DualQuat::fromRigid(q, {1, 2, 3}), {1, 1, 1}},
        {math::DualQuat::fromRigid(-q, {1, 2, 3}), {1, 1, 1}}};
    const glm::vec3 p(0.5f, -0.25f, 2.0f);
    const anim::SkinnedVertex v =
        anim::skinDualQuat(palette, p, {0, 0, 1}, {0, 1, 0, 0}, {0.5f, 0.5f, 0.0f, 0.0f});
    const glm::vec3 expected = q * p + glm::vec3(1, 2, 3);
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(v.position[a], expected[a], 1e-5f);
}

TEST(SkinningDualQuat, ScaleIsBlendedLinearlyAndNormalsByItsInverse) {
    // Two joints that only scale: 2 and 4 along x, blended half and half -> 3 along x.
    const std::vector<glm::mat4> matrices = {glm::scale(glm::mat4(1.0f), {2, 1, 1}),
                                             glm::scale(glm::mat4(1.0f), {4, 1, 1})};
    const auto palette = anim::dualQuatPalette(matrices);
    const glm::vec3 n = glm::normalize(glm::vec3(1, 1, 0));
    const anim::SkinnedVertex v =
        anim::skinDualQuat(palette, {1, 1, 1}, n, {0, 1, 0, 0}, {0.5f, 0.5f, 0, 0});
    EXPECT_NEAR(v.position.x, 3.0f, 1e-6f);
    EXPECT_NEAR(v.position.y, 1.0f, 1e-6f);
    const glm::vec3 expected = glm::normalize(glm::vec3(1.0f / 3.0f, 1.0f, 0.0f));
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(v.normal[a], expected[a], 1e-6f);
}

} // namespace
} // namespace mfx::test
