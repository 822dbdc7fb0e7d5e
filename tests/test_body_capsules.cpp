// The body as capsules (core/anim/body_capsules.h): fitted once in the bind pose, posed by their
// joints, they hold the skinned vertices of the built-in fighter and of the real models through
// their clips, stay close to the surface, and move with their bones.
#include "core/anim/body_capsules.h"
#include "core/anim/fighter.h"
#include "core/anim/gltf_import.h"
#include "core/anim/skinning.h"

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace mfx::test {
namespace {

struct Coverage {
    size_t vertices = 0;
    size_t within = 0;   // inside a capsule or within `tolerance` of one
    float farthest = 0;  // the largest distance outside every capsule
    float meanDepth = 0; // mean over vertices of how far inside their nearest surface they lie
};

// Every skinned vertex of `c` at clip time t against the posed capsules.
Coverage coverage(const anim::Character& c, const std::vector<anim::BodyCapsule>& capsules,
                  const anim::Clip* clip, float t, float tolerance) {
    const anim::Pose pose = anim::samplePose(c, clip, t);
    std::vector<anim::PosedCapsule> posed;
    for (const anim::BodyCapsule& capsule : capsules)
        posed.push_back(anim::poseCapsule(capsule, pose));
    Coverage r;
    double depth = 0.0;
    for (const anim::Mesh& mesh : c.meshes)
        for (const anim::Primitive& primitive : mesh.primitives) {
            if (primitive.skin < 0 && primitive.node < 0) continue;
            for (const anim::SkinnedVertex& v : anim::skinPrimitive(c, primitive, pose)) {
                float nearest = 1e30f;
                for (const anim::PosedCapsule& p : posed)
                    nearest = std::min(nearest, anim::signedDistance(p, v.position));
                ++r.vertices;
                r.within += nearest <= tolerance ? 1 : 0;
                r.farthest = std::max(r.farthest, nearest);
                depth += double(-nearest);
            }
        }
    r.meanDepth = r.vertices > 0 ? float(depth / double(r.vertices)) : 0.0f;
    return r;
}

// The largest extent of the character's bind-pose vertices (its size, for tolerances).
float size(const anim::Character& c) {
    glm::vec3 low(1e30f), high(-1e30f);
    const anim::Pose rest = anim::samplePose(c, nullptr, 0.0f);
    for (const anim::Mesh& mesh : c.meshes)
        for (const anim::Primitive& primitive : mesh.primitives)
            for (const anim::SkinnedVertex& v : anim::skinPrimitive(c, primitive, rest)) {
                low = glm::min(low, v.position);
                high = glm::max(high, v.position);
            }
    return glm::length(high - low);
}

// Through the roundhouse kick, 98% of the fighter's vertices lie inside a capsule or within 1 cm
// of one (the rest are in joints' blend regions, where the skinned surface bends and the capsules
// stay rigid; none farther than 4 cm), and the capsules are tight: a vertex lies on average
// 1.5-3 cm inside its nearest capsule's surface (a capsule much larger than the limb would put
// them deeper).
TEST(BodyCapsules, TheFightersCapsulesHoldItsVerticesThroughTheKick) {
    const anim::Character fighter = anim::makeFighter();
    const std::vector<anim::BodyCapsule> capsules = anim::fitBodyCapsules(fighter);
    EXPECT_GE(capsules.size(), 10u);
    const anim::Clip* kick = fighter.findClip("roundhouse_kick");
    ASSERT_NE(kick, nullptr);
    for (float t : {0.0f, 0.3f, 0.6f, 0.9f}) {
        const Coverage r = coverage(fighter, capsules, kick, t, 0.01f);
        const double share = double(r.within) / double(r.vertices);
        std::printf("%zu capsules, t %.1f s: %.1f%% of %zu vertices within 1 cm, farthest %.3f m "
                    "outside, mean depth %.3f m\n",
                    capsules.size(), double(t), 100.0 * share, r.vertices, double(r.farthest),
                    double(r.meanDepth));
        EXPECT_GE(share, 0.98) << "t " << t;
        EXPECT_LE(r.farthest, 0.04f) << "t " << t;
        EXPECT_GT(r.meanDepth, 0.0f);
        EXPECT_LE(r.meanDepth, 0.03f) << "t " << t;
    }
}

// The real models of ../shared/assets, in their first clip: 95% of the vertices within 1% of the
// model's size of a capsule.
TEST(BodyCapsules, TheRealModelsCapsulesHoldTheirVertices) {
    for (const char* file :
         {"RiggedFigure.gltf", "RiggedSimple.gltf", "RobotExpressive.glb", "SimpleSkin.gltf"}) {
        const std::string path = std::string(MFX_SOURCE_DIR) + "/../shared/assets/" + file;
        Result<anim::Character> loaded = anim::importGltf(path);
        ASSERT_TRUE(loaded.ok()) << file << ": " << loaded.error().message;
        const anim::Character& c = loaded.value();
        const std::vector<anim::BodyCapsule> capsules = anim::fitBodyCapsules(c);
        ASSERT_FALSE(capsules.empty()) << file;
        const anim::Clip* clip = c.clips.empty() ? nullptr : &c.clips.front();
        const float tolerance = 0.01f * size(c);
        for (float fraction : {0.0f, 0.5f}) {
            const float t = clip ? fraction * clip->duration : 0.0f;
            const Coverage r = coverage(c, capsules, clip, t, tolerance);
            const double share = double(r.within) / double(r.vertices);
            std::printf("%s: %zu capsules, t %.2f s: %.1f%% of %zu vertices within %.3f\n", file,
                        capsules.size(), double(t), 100.0 * share, r.vertices, double(tolerance));
            EXPECT_GE(share, 0.95) << file << " t " << t;
        }
    }
}

// A posed capsule is its node's: moved and turned with the node's world matrix, its radius
// scaled by the matrix's scale.
TEST(BodyCapsules, APosedCapsuleFollowsItsNode) {
    anim::Character c;
    c.nodes.push_back({"root", -1, {}});
    anim::Pose pose;
    pose.local.resize(1);
    const glm::mat4 world = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 2.0f, 3.0f)) *
                            glm::rotate(glm::mat4(1.0f), 1.5707963f, glm::vec3(0, 0, 1)) *
                            glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));
    pose.world = {world};
    const anim::BodyCapsule capsule{0, {0, 0, 0}, {1, 0, 0}, 0.25f, 10};
    const anim::PosedCapsule posed = anim::poseCapsule(capsule, pose);
    EXPECT_NEAR(glm::length(posed.a - glm::vec3(1, 2, 3)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(posed.b - glm::vec3(1, 4, 3)), 0.0f, 1e-5f); // x turned onto y, x2
    EXPECT_NEAR(posed.radius, 0.5f, 1e-5f);
    EXPECT_NEAR(anim::signedDistance(posed, glm::vec3(1, 3, 3)), -0.5f, 1e-5f);
    EXPECT_NEAR(anim::signedDistance(posed, glm::vec3(2, 3, 3)), 0.5f, 1e-5f);
    EXPECT_NEAR(anim::signedDistance(posed, glm::vec3(1, 5, 3)), 0.5f, 1e-5f); // past end b
}

} // namespace
} // namespace mfx::test
