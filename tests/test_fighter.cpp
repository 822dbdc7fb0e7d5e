// The built-in fighter: a valid, deterministic character of the advertised shape, with
// non-overlapping UVs, smooth normals, a sword bound to the right hand, and clips that move it.
#include "core/anim/fighter.h"
#include "core/anim/skinning.h"

#include <cmath>
#include <gtest/gtest.h>

namespace mfx::test {
namespace {

size_t triangleCount(const anim::Character& c) {
    size_t n = 0;
    for (const anim::Mesh& m : c.meshes)
        for (const anim::Primitive& p : m.primitives)
            n += p.indices.size() / 3;
    return n;
}

TEST(Fighter, IsAValidCharacterOfTheAdvertisedShape) {
    const anim::Character c = anim::makeFighter();
    const Status valid = anim::checkInvariants(c);
    ASSERT_TRUE(valid.ok()) << valid.error().message;
    EXPECT_EQ(c.nodes.size(), 21u);
    ASSERT_EQ(c.skins.size(), 1u);
    EXPECT_EQ(c.skins[0].joints.size(), 21u);
    const size_t triangles = triangleCount(c);
    RecordProperty("triangles", std::to_string(triangles));
    EXPECT_GE(triangles, 2000u);
    EXPECT_LE(triangles, 10000u);
    for (const char* name : {"hips", "head", "hand_r", "hand_l", "foot_r", "foot_l"})
        EXPECT_TRUE(c.findNode(name).has_value()) << name;
    for (const char* name :
         {"idle", "roundhouse_kick", "straight_punch", "sword_slash", "spin", "hit_react"}) {
        const anim::Clip* clip = c.findClip(name);
        ASSERT_NE(clip, nullptr) << name;
        EXPECT_GE(clip->duration, 0.4f) << name;
        EXPECT_LE(clip->duration, 1.5f) << name;
    }
    ASSERT_NE(c.findClip("kick_slash"), nullptr);
}

TEST(Fighter, IsDeterministic) {
    const anim::Character a = anim::makeFighter(), b = anim::makeFighter();
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t m = 0; m < a.meshes.size(); ++m)
        for (size_t p = 0; p < a.meshes[m].primitives.size(); ++p) {
            EXPECT_EQ(a.meshes[m].primitives[p].positions, b.meshes[m].primitives[p].positions);
            EXPECT_EQ(a.meshes[m].primitives[p].indices, b.meshes[m].primitives[p].indices);
        }
}

TEST(Fighter, SwordIsItsOwnMeshBoundToTheRightHand) {
    const anim::Character c = anim::makeFighter();
    const anim::Mesh* sword = c.findMesh("sword");
    ASSERT_NE(sword, nullptr);
    const uint32_t hand = uint32_t(*c.findNode("hand_r")); // the skin lists nodes in order
    for (const anim::Primitive& p : sword->primitives)
        for (size_t v = 0; v < p.joints.size(); ++v) {
            ASSERT_EQ(p.joints[v].x, hand);
            ASSERT_EQ(p.weights[v].x, 1.0f);
        }
}

// Rasterises every triangle's UVs into a bitmap: no texel centre may lie inside two triangles.
TEST(Fighter, UvsAreInTheUnitSquareAndDoNotOverlap) {
    const anim::Character c = anim::makeFighter();
    const int size = 1024;
    std::vector<uint8_t> covered(size_t(size) * size, 0);
    size_t overlaps = 0;
    for (const anim::Mesh& m : c.meshes)
        for (const anim::Primitive& p : m.primitives) {
            ASSERT_EQ(p.uvs.size(), p.positions.size()) << m.name;
            for (const glm::vec2& uv : p.uvs) {
                ASSERT_GE(uv.x, 0.0f);
                ASSERT_LE(uv.x, 1.0f);
                ASSERT_GE(uv.y, 0.0f);
                ASSERT_LE(uv.y, 1.0f);
            }
            for (size_t i = 0; i < p.indices.size(); i += 3) {
                const glm::vec2 a = p.uvs[p.indices[i]] * float(size);
                const glm::vec2 b = p.uvs[p.indices[i + 1]] * float(size);
                const glm::vec2 d = p.uvs[p.indices[i + 2]] * float(size);
                const glm::vec2 lo = glm::min(a, glm::min(b, d)), hi = glm::max(a, glm::max(b, d));
                auto edge = [](glm::vec2 p0, glm::vec2 p1, glm::vec2 q) {
                    return (p1.x - p0.x) * (q.y - p0.y) - (p1.y - p0.y) * (q.x - p0.x);
                };
                const float area = edge(a, b, d);
                if (area == 0.0f) continue;
                for (int y = int(lo.y); y <= int(hi.y) && y < size; ++y)
                    for (int x = int(lo.x); x <= int(hi.x) && x < size; ++x) {
                        const glm::vec2 q(float(x) + 0.5f, float(y) + 0.5f);
                        const float w0 = edge(b, d, q) / area, w1 = edge(d, a, q) / area,
                                    w2 = edge(a, b, q) / area;
                        if (w0 <= 0.0f || w1 <= 0.0f || w2 <= 0.0f) continue; // strictly inside
                        if (covered[size_t(y) * size + size_t(x)]++) ++overlaps;
                    }
            }
        }
    EXPECT_EQ(overlaps, 0u);
}

TEST(Fighter, NormalsAreUnitAndSmoothAcrossSeams) {
    const anim::Character c = anim::makeFighter();
    for (const anim::Mesh& m : c.meshes)
        for (const anim::Primitive& p : m.primitives)
            for (size_t v = 0; v < p.normals.size(); ++v) {
                ASSERT_NEAR(glm::length(p.normals[v]), 1.0f, 1e-5f) << m.name << " " << v;
                // The seam vertex of each ring duplicates the first one: same normal.
                if (v % 17 == 16) {
                    ASSERT_LT(glm::length(p.normals[v] - p.normals[v - 16]), 1e-5f) << m.name;
                }
            }
}

glm::vec3 jointWorld(const anim::Character& c, const char* clip, float t, const char* joint) {
    const anim::Pose pose = anim::samplePose(c, c.findClip(clip), t, anim::Wrap::Clamp);
    return glm::vec3(pose.world[size_t(*c.findNode(joint))][3]);
}

TEST(Fighter, ClipsStrike) {
    const anim::Character c = anim::makeFighter();
    // The kick: the right foot rises above the hips at the strike and comes back down.
    const glm::vec3 footStart = jointWorld(c, "roundhouse_kick", 0.0f, "foot_r");
    const glm::vec3 footStrike = jointWorld(c, "roundhouse_kick", 0.4f, "foot_r");
    const glm::vec3 hipsStrike = jointWorld(c, "roundhouse_kick", 0.4f, "hips");
    RecordProperty("kickFootHeight", std::to_string(footStrike.y));
    EXPECT_LT(footStart.y, 0.2f);
    EXPECT_GT(footStrike.y, hipsStrike.y);
    // The punch: the right hand reaches forward (+z) at the strike.
    const glm::vec3 handStart = jointWorld(c, "straight_punch", 0.0f, "hand_r");
    const glm::vec3 handStrike = jointWorld(c, "straight_punch", 0.2f, "hand_r");
    RecordProperty("punchReach", std::to_string(handStrike.z - handStart.z));
    EXPECT_GT(handStrike.z - handStart.z, 0.25f);
    // The spin ends facing where it started.
    const glm::vec3 a = jointWorld(c, "spin", 0.0f, "hand_l");
    const glm::vec3 b = jointWorld(c, "spin", 0.8f, "hand_l");
    EXPECT_LT(glm::length(a - b), 1e-3f);
    // Skinned positions stay finite in every clip.
    for (const anim::Clip& clip : c.clips)
        for (int i = 0; i <= 10; ++i) {
            const anim::Pose pose =
                anim::samplePose(c, &clip, clip.duration * float(i) / 10.0f, anim::Wrap::Clamp);
            for (const anim::Mesh& m : c.meshes)
                for (const anim::Primitive& p : m.primitives)
                    for (const anim::SkinnedVertex& v : anim::skinPrimitive(c, p, pose))
                        ASSERT_TRUE(std::isfinite(v.position.x + v.position.y + v.position.z))
                            << clip.name;
        }
}

// The combo plays the roundhouse kick, then the sword slash from where the kick ended: every joint
// where the one clip or the other puts it, at their own times.
TEST(Fighter, TheComboIsTheKickThenTheSlash) {
    const anim::Character c = anim::makeFighter();
    const anim::Clip* combo = c.findClip("kick_slash");
    ASSERT_NE(combo, nullptr);
    const float kick = c.findClip("roundhouse_kick")->duration;
    EXPECT_FLOAT_EQ(combo->duration, kick + c.findClip("sword_slash")->duration);
    for (const char* joint : {"hips", "foot_r", "hand_r", "head", "toe_l"})
        for (float t = 0.0f; t <= combo->duration; t += 0.05f) {
            const glm::vec3 expected = t < kick ? jointWorld(c, "roundhouse_kick", t, joint)
                                                : jointWorld(c, "sword_slash", t - kick, joint);
            const glm::vec3 got = jointWorld(c, "kick_slash", t, joint);
            EXPECT_LT(glm::length(got - expected), 1e-4f) << joint << " at " << t << " s";
        }
}

// The hit reaction: from the stance the head is thrown back (-z, away from a blow from the front)
// within 0.08 s, and the clip ends in the stance again (every clip joins the others without a
// jump).
TEST(Fighter, TheHitReactionThrowsTheHeadBackAndRecovers) {
    const anim::Character c = anim::makeFighter();
    const anim::Clip* react = c.findClip("hit_react");
    ASSERT_NE(react, nullptr);
    const glm::vec3 stance = jointWorld(c, "idle", 0.0f, "head");
    const glm::vec3 start = jointWorld(c, "hit_react", 0.0f, "head");
    const glm::vec3 jolt = jointWorld(c, "hit_react", 0.08f, "head");
    const glm::vec3 end = jointWorld(c, "hit_react", react->duration, "head");
    RecordProperty("headThrownBackMetres", std::to_string(start.z - jolt.z));
    EXPECT_LT(glm::length(start - stance), 1e-4f);
    EXPECT_GT(start.z - jolt.z, 0.15f);
    EXPECT_LT(jolt.y, start.y);
    EXPECT_LT(glm::length(end - stance), 1e-4f);
    for (const char* joint : {"hand_l", "hand_r", "foot_l", "foot_r", "hips"})
        EXPECT_LT(glm::length(jointWorld(c, "hit_react", react->duration, joint) -
                              jointWorld(c, "idle", 0.0f, joint)),
                  1e-4f)
            << joint;
}

} // namespace
} // namespace mfx::test
