// The toon style of the scene pass (render/character_pass.h, shaders/render/character.frag,
// outline.vert): a lit sphere shows exactly the ramp's levels, the outline is as many pixels wide
// near and far, and stays closed around a flat-shaded cube (split normals at every edge).
#include "core/gpu/commands.h"
#include "render/character_pass.h"
#include "render/image_output.h"
#include "render/render_target.h"
#include "tests/gpu_test.h"
#include "tests/scene_render_util.h"

#include <glm/gtc/constants.hpp>
#include <map>

namespace mfx::test {
namespace {

constexpr uint32_t kSize = 256;

// A unit-diameter UV sphere at the origin, smooth normals, as an unskinned character.
anim::Character sphere() {
    anim::Primitive p;
    const int rings = 48, segments = 96;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s) {
            const float theta = glm::pi<float>() * float(r) / rings;
            const float phi = 2.0f * glm::pi<float>() * float(s) / segments;
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                              std::sin(theta) * std::sin(phi));
            p.positions.push_back(0.5f * n);
            p.normals.push_back(n);
        }
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const uint32_t a = uint32_t(r * (segments + 1) + s), b = a + uint32_t(segments + 1);
            // Counter-clockwise seen from outside.
            p.indices.insert(p.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
        }
    p.baseColor = glm::vec4(0.9f, 0.25f, 0.2f, 1.0f);
    anim::Character c;
    c.meshes.push_back({"ball", {p}});
    return c;
}

// A cube of side 0.8, flat-shaded: four vertices of its own on each face.
anim::Character flatCube() {
    anim::Primitive p;
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {-1.0f, 1.0f}) {
            glm::vec3 n(0.0f);
            n[axis] = sign;
            const glm::vec3 u = axis == 1 ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
            const glm::vec3 v = glm::cross(n, u);
            const uint32_t base = uint32_t(p.positions.size());
            for (glm::vec2 c :
                 {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
                p.positions.push_back(0.4f * (n + c.x * u + c.y * v));
                p.normals.push_back(n);
            }
            p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        }
    p.baseColor = glm::vec4(0.9f, 0.25f, 0.2f, 1.0f);
    anim::Character c;
    c.meshes.push_back({"cube", {p}});
    return c;
}

// A scene of the object alone: no stage, no shadow, a key light from the upper left front.
scene::Scene objectScene(float distance, uint32_t bands, float outline) {
    scene::Scene s;
    s.stage.floor = s.stage.backdrop = false;
    s.lights[0].direction = glm::vec3(0.6f, -0.5f, -0.6f);
    s.lights[0].shadow = false;
    s.camera.position = glm::vec3(0.0f, 0.0f, distance);
    s.camera.target = glm::vec3(0.0f);
    s.characters[0].style = scene::CharacterStyle::Toon;
    s.characters[0].toonBands = bands;
    s.characters[0].rim = 0.0f;
    s.characters[0].outlineWidth = outline;
    s.characters[0].outlineColour = glm::vec3(0.0f, 1.0f, 0.0f);
    return s;
}

class ToonShadingTest : public GpuTest {
protected:
    // The object drawn alone on black, one sample per pixel, RGBA8 (sRGB).
    static std::vector<uint8_t> draw(const anim::Character& object, const scene::Scene& s,
                                     const std::string& name) {
        render::RenderTarget target = render::createRenderTarget(ctx(), kSize, kSize);
        render::CharacterPass pass(ctx(), object, s);
        const render::SceneCamera camera = render::makeCamera(s.camera, 1.0f);
        gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
            pass.skin(cmd, anim::Pose{}, glm::mat4(1.0f));
            render::beginRendering(cmd, target, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
            pass.draw(cmd, camera);
            pass.drawOutline(cmd, kSize, kSize);
            render::endRendering(cmd);
        });
        std::vector<uint8_t> rgba = render::readColor(ctx(), target);
        const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/toon";
        EXPECT_TRUE(render::ensureOutputDirectory(dir).ok());
        EXPECT_TRUE(render::writePng(dir + "/" + name + ".png", kSize, kSize, rgba).ok());
        return rgba;
    }

    // The red values that cover at least `share` of the object's pixels (green 0: not outline).
    static std::vector<int> levels(const std::vector<uint8_t>& rgba, double share) {
        std::map<int, size_t> counts;
        size_t covered = 0;
        for (size_t p = 0; p < rgba.size(); p += 4)
            if (rgba[p] > 0 && rgba[p + 1] < rgba[p]) {
                ++counts[rgba[p]];
                ++covered;
            }
        std::vector<int> out;
        for (auto [value, count] : counts)
            if (double(count) >= share * double(covered)) out.push_back(value);
        return out;
    }

    // Outline pixels (green above red) met from the left edge along row `y` before the object.
    static int outlineFromLeft(const std::vector<uint8_t>& rgba, uint32_t y) {
        int count = 0;
        for (uint32_t x = 0; x < kSize; ++x) {
            const uint8_t* p = &rgba[(size_t(y) * kSize + x) * 4];
            const bool outline = p[1] > p[0];
            const bool object = p[0] > p[1];
            if (object) return count;
            if (outline) ++count;
        }
        return -1; // the row misses the object
    }
};

TEST_F(ToonShadingTest, ALitSphereShowsTheRampsLevels) {
    const anim::Character ball = sphere();
    for (uint32_t bands : {2u, 3u, 4u}) {
        const std::vector<uint8_t> rgba =
            draw(ball, objectScene(3.0f, bands, 0.0f), "bands" + std::to_string(bands));
        const std::vector<int> found = levels(rgba, 0.02);
        std::string list;
        for (int v : found)
            list += std::to_string(v) + " ";
        EXPECT_EQ(found.size(), size_t(bands)) << bands << " bands; red levels over 2%: " << list;
    }
}

TEST_F(ToonShadingTest, TheLitStyleIsAGradient) {
    scene::Scene s = objectScene(3.0f, 3, 0.0f);
    s.characters[0].style = scene::CharacterStyle::Lit;
    const std::vector<uint8_t> rgba = draw(sphere(), s, "lit");
    EXPECT_LE(levels(rgba, 0.02).size(), 1u) << "no tone covers 2% of a smooth shading";
    EXPECT_GT(levels(rgba, 0.0).size(), 40u);
}

TEST_F(ToonShadingTest, TheOutlineIsAsWideNearAndFar) {
    const anim::Character ball = sphere();
    for (float width : {2.0f, 4.0f}) {
        for (float distance : {2.5f, 6.0f}) {
            const std::vector<uint8_t> rgba =
                draw(ball, objectScene(distance, 3, width),
                     "outline_" + std::to_string(int(width)) + "_" + std::to_string(int(distance)));
            const int measured = outlineFromLeft(rgba, kSize / 2);
            EXPECT_NEAR(measured, width, 1.0) << "width " << width << " at distance " << distance;
        }
    }
}

TEST_F(ToonShadingTest, TheOutlineStaysClosedAroundAFlatShadedCube) {
    scene::Scene s = objectScene(3.0f, 3, 3.0f);
    s.camera.position = glm::vec3(1.6f, 1.3f, 2.2f); // three faces seen, corners on the silhouette
    const std::vector<uint8_t> rgba = draw(flatCube(), s, "cube");
    int rows = 0;
    for (uint32_t y = 0; y < kSize; ++y) {
        const int outline = outlineFromLeft(rgba, y);
        if (outline < 0) continue;
        ++rows;
        EXPECT_GE(outline, 1) << "row " << y << " meets the cube without an outline";
    }
    EXPECT_GT(rows, 60);
}

// Imported characters in the toon style, through the whole frame: the flat-shaded RiggedFigure
// (split normals everywhere) and RobotExpressive (several meshes and materials). Each is outlined
// wherever it meets the background from the left.
TEST_F(ToonShadingTest, ImportedCharactersAreOutlinedAllRound) {
    for (const char* file : {"RiggedFigure.gltf", "RobotExpressive.glb"}) {
        scene::Scene s =
            scene::previewScene(std::string(MFX_SOURCE_DIR) + "/../shared/assets/" + file);
        s.effects.clear();
        s.stage.floor = s.stage.backdrop = false;
        s.characters[0].style = scene::CharacterStyle::Toon;
        s.characters[0].rim = 0.0f;
        s.characters[0].outlineColour = glm::vec3(0.0f, 1.0f, 0.0f);
        s.characters[0].outlineWidth = 2.0f;
        s.output.frames = 3;
        s.post.bloom = 0.0f; // its glow would be the first pixel off the background
        Result<DrawnScene> drawn = drawScene(ctx(), s, kSize, kSize, VK_SAMPLE_COUNT_1_BIT);
        ASSERT_TRUE(drawn) << drawn.error().message;
        drawn.value().playTo(ctx());
        const std::vector<uint8_t> rgba =
            render::readColor(ctx(), drawn.value().renderer->output());
        EXPECT_TRUE(render::writePng(std::string(MFX_TEST_OUTPUT_DIR) + "/toon/" + file + ".png",
                                     kSize, kSize, rgba)
                        .ok());
        // Each row meeting the character: the first pixel off the background is the outline's.
        int rows = 0, outlined = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                const uint8_t* p = &rgba[(size_t(y) * kSize + x) * 4];
                // The background: the clear colour, as in the top-left corner.
                if (std::abs(p[0] - rgba[0]) + std::abs(p[1] - rgba[1]) + std::abs(p[2] - rgba[2]) <
                    6)
                    continue;
                ++rows;
                outlined += p[1] > 2 * std::max(p[0], p[2]) ? 1 : 0;
                break;
            }
        EXPECT_GT(rows, 100) << file;
        EXPECT_GE(outlined, rows - 2) << file << ": of " << rows << " rows";
    }
}

} // namespace
} // namespace mfx::test
