// The scene pass: the skinned fighter on its stage, seen by the scene's camera. Checks where the
// character lands in the picture against its skinned vertices projected on the CPU, and writes the
// picture for a look.
#include "core/anim/fighter.h"
#include "core/gpu/commands.h"
#include "render/character_pass.h"
#include "render/image_output.h"
#include "render/render_target.h"
#include "tests/gpu_test.h"

#include <glm/gtc/matrix_transform.hpp>
#include <set>

namespace mfx::test {
namespace {

using CharacterPassTest = GpuTest;

TEST_F(CharacterPassTest, FighterLandsWhereItsVerticesProject) {
    const anim::Character fighter = anim::makeFighter();
    const scene::Scene s = scene::kickScene();
    const uint32_t width = 320, height = 180;
    render::RenderTarget target = render::createRenderTarget(ctx(), width, height);
    render::CharacterPass pass(ctx(), fighter, s);
    const render::SceneCamera camera = render::makeCamera(s.camera, float(width) / float(height));
    const anim::Pose pose =
        anim::samplePose(fighter, fighter.findClip("roundhouse_kick"), 0.45f, anim::Wrap::Clamp);
    gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
        pass.skin(cmd, pose, glm::mat4(1.0f));
        render::beginRendering(cmd, target, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        pass.draw(cmd, camera);
        render::endRendering(cmd);
    });
    const std::vector<uint8_t> rgba = render::readColor(ctx(), target);
    const std::vector<float> depth = render::readDepth(ctx(), target);
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/character_pass";
    ASSERT_TRUE(render::ensureOutputDirectory(dir).ok());
    ASSERT_TRUE(render::writePng(dir + "/kick.png", width, height, rgba).ok());

    // Every skinned vertex projected on the CPU (no depth test): the pixels the character can
    // cover. The body's vertices in front of the stage must have drawn something nearer than the
    // floor and backdrop there.
    size_t inside = 0, nearer = 0;
    for (const anim::Mesh& mesh : fighter.meshes)
        for (const anim::Primitive& p : mesh.primitives) {
            const auto skinned = anim::skinPrimitive(fighter, p, pose);
            for (size_t v = 0; v < skinned.size(); v += 7) {
                const glm::vec4 clip = camera.viewProjection * glm::vec4(skinned[v].position, 1.0f);
                const glm::vec3 ndc = glm::vec3(clip) / clip.w;
                const int x = int((ndc.x * 0.5f + 0.5f) * float(width));
                const int y = int((0.5f - ndc.y * 0.5f) * float(height)); // top row first
                if (x < 1 || y < 1 || x >= int(width) - 1 || y >= int(height) - 1) continue;
                ++inside;
                // The drawn depth there is at most this vertex's (something as near or nearer),
                // within a pixel: a silhouette vertex may round to a pixel just off the surface.
                float drawn = 1.0f;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx)
                        drawn = std::min(drawn, depth[size_t(y + dy) * width + size_t(x + dx)]);
                if (drawn <= ndc.z + 1e-4f) ++nearer;
            }
        }
    EXPECT_GT(inside, 100u);
    EXPECT_EQ(nearer, inside);
    // The picture is not one colour: character, floor and backdrop differ.
    size_t changes = 0;
    for (size_t i = 4; i < rgba.size(); i += 4)
        changes += rgba[i] != rgba[i - 4] ? 1 : 0;
    EXPECT_GT(changes, 1000u);
}

// With 4x multisampling the silhouette's edge pixels blend the character with what is behind it:
// many more distinct colours along the edges than in the single-sampled picture, the same
// picture otherwise (the resolved depth is sample 0's).
TEST_F(CharacterPassTest, MultisamplingSmoothsTheEdges) {
    const anim::Character fighter = anim::makeFighter();
    const scene::Scene s = scene::kickScene();
    const uint32_t width = 160, height = 90;
    const render::SceneCamera camera = render::makeCamera(s.camera, 16.0f / 9.0f);
    const anim::Pose pose =
        anim::samplePose(fighter, fighter.findClip("roundhouse_kick"), 0.45f, anim::Wrap::Clamp);
    auto renderWith = [&](VkSampleCountFlagBits samples, std::vector<float>* depth) {
        render::RenderTarget target = render::createRenderTarget(ctx(), width, height, samples);
        render::CharacterPass pass(ctx(), fighter, s, samples);
        gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
            pass.skin(cmd, pose, glm::mat4(1.0f));
            render::beginRendering(cmd, target, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
            pass.draw(cmd, camera);
            render::endRendering(cmd);
        });
        if (depth) *depth = render::readDepth(ctx(), target);
        return render::readColor(ctx(), target);
    };
    const VkSampleCountFlagBits four = render::supportedSamples(ctx(), VK_SAMPLE_COUNT_4_BIT);
    ASSERT_EQ(four, VK_SAMPLE_COUNT_4_BIT) << "lavapipe supports 4x";
    std::vector<float> depth1, depth4;
    const auto one = renderWith(VK_SAMPLE_COUNT_1_BIT, &depth1);
    const auto many = renderWith(four, &depth4);
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/character_pass";
    ASSERT_TRUE(render::ensureOutputDirectory(dir).ok());
    ASSERT_TRUE(render::writePng(dir + "/kick_msaa.png", width, height, many).ok());
    auto colours = [](const std::vector<uint8_t>& rgba) {
        std::set<uint32_t> distinct;
        for (size_t i = 0; i < rgba.size(); i += 4)
            distinct.insert(uint32_t(rgba[i]) | uint32_t(rgba[i + 1]) << 8 |
                            uint32_t(rgba[i + 2]) << 16);
        return distinct.size();
    };
    size_t differing = 0;
    for (size_t i = 0; i < one.size(); i += 4)
        differing += (one[i] != many[i] || one[i + 1] != many[i + 1] || one[i + 2] != many[i + 2]);
    std::printf("distinct colours: %zu single-sampled, %zu with 4x; %zu of %u pixels differ\n",
                colours(one), colours(many), differing, width * height);
    EXPECT_GT(colours(many), colours(one) + 50);
    EXPECT_LT(differing, size_t(width) * height / 5); // edges only, not the whole picture
    // Sample 0 sits off the pixel centre, so depths differ a little everywhere, and a lot only
    // where an edge passes between the two positions.
    size_t depthDiffers = 0;
    for (size_t i = 0; i < depth1.size(); ++i)
        depthDiffers += std::abs(depth1[i] - depth4[i]) > 1e-3f ? 1 : 0;
    EXPECT_LT(depthDiffers, depth1.size() / 20);
}

// The key light's shadow: the floor where the character's shadow falls (found by casting a ray
// from a body point along the light to the floor) is darker than the same spot without shadows.
TEST_F(CharacterPassTest, KeyLightCastsTheCharactersShadowOnTheFloor) {
    const anim::Character fighter = anim::makeFighter();
    scene::Scene s = scene::kickScene();
    s.camera.position = glm::vec3(0.0f, 4.0f, 4.0f); // looking down at the floor around the feet
    s.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
    const uint32_t width = 160, height = 120;
    const render::SceneCamera camera = render::makeCamera(s.camera, float(width) / float(height));
    const anim::Pose pose = anim::samplePose(fighter, fighter.findClip("idle"), 0.0f);
    auto renderWith = [&](bool shadows) {
        scene::Scene copy = s;
        copy.lights[0].shadow = shadows;
        render::RenderTarget target = render::createRenderTarget(ctx(), width, height);
        render::CharacterPass pass(ctx(), fighter, copy);
        gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
            pass.skin(cmd, pose, glm::mat4(1.0f));
            pass.shadow(cmd);
            render::beginRendering(cmd, target, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
            pass.draw(cmd, camera);
            render::endRendering(cmd);
        });
        return render::readColor(ctx(), target);
    };
    const auto lit = renderWith(false), shadowed = renderWith(true);
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/character_pass";
    ASSERT_TRUE(render::ensureOutputDirectory(dir).ok());
    ASSERT_TRUE(render::writePng(dir + "/shadow.png", width, height, shadowed).ok());
    // Where the chest's shadow lands on the floor (y = 0), along the light's direction.
    const glm::vec3 chest = glm::vec3(pose.world[size_t(*fighter.findNode("chest"))][3]);
    const glm::vec3 d = glm::normalize(s.lights[0].direction);
    const glm::vec3 onFloor = chest + d * (-chest.y / d.y);
    const glm::vec4 clip = camera.viewProjection * glm::vec4(onFloor, 1.0f);
    const int x = int((clip.x / clip.w * 0.5f + 0.5f) * float(width));
    const int y = int((0.5f - clip.y / clip.w * 0.5f) * float(height));
    ASSERT_TRUE(x > 0 && y > 0 && x < int(width) && y < int(height)) << x << "," << y;
    const size_t i = (size_t(y) * width + size_t(x)) * 4;
    const int before = lit[i] + lit[i + 1] + lit[i + 2];
    const int after = shadowed[i] + shadowed[i + 1] + shadowed[i + 2];
    std::printf("floor at the chest's shadow (%d, %d): brightness %d lit, %d shadowed\n", x, y,
                before, after);
    EXPECT_LT(after, before * 3 / 4);
    // And a floor spot far from the character is the same in both.
    const size_t far = (size_t(height - 3) * width + 3) * 4;
    EXPECT_NEAR(lit[far], shadowed[far], 2);
}

} // namespace
} // namespace mfx::test
