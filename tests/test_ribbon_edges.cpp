// The edges of speed-line ribbons and sheets: where the pieces of a line meet, within a frame's
// segment and at the weld between two frames' segments, the ribbon's edges continue one another
// (render/kinds/speed_lines_pass.h, shaders/render/ribbon_joins.comp); and the hero's slash arc, a
// sheet, has an outer edge that is one smooth curve at 1920x1080, where the ribbons it was drawn
// with before left stair steps.
#include "core/anim/fighter.h"
#include "core/gpu/commands.h"
#include "core/scene/kinds/trail_effects.h"
#include "core/trajectory/trajectory_source.h"
#include "render/bake_renderer.h"
#include "render/image_output.h"
#include "sim/scene_simulation.h"
#include "tests/gpu_test.h"
#include "tests/moving_point.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

namespace mfx::test {
namespace {

// Alpha of an RGBA float picture at (x, y) in pixels (pixel centres at + 0.5), bilinear; 0
// outside.
float alphaAt(const std::vector<float>& rgba, uint32_t width, uint32_t height, glm::vec2 p) {
    const glm::vec2 q = p - 0.5f;
    const int x0 = int(std::floor(q.x)), y0 = int(std::floor(q.y));
    const float fx = q.x - float(x0), fy = q.y - float(y0);
    auto a = [&](int x, int y) {
        if (x < 0 || y < 0 || x >= int(width) || y >= int(height)) return 0.0f;
        return rgba[(size_t(y) * width + size_t(x)) * 4 + 3];
    };
    return (1 - fy) * ((1 - fx) * a(x0, y0) + fx * a(x0 + 1, y0)) +
           fy * ((1 - fx) * a(x0, y0 + 1) + fx * a(x0 + 1, y0 + 1));
}

// The alpha of an RGBA float picture as an 8-bit grey PNG in the tests' output folder.
void writeAlpha(const std::string& name, const std::vector<float>& rgba, uint32_t width,
                uint32_t height) {
    std::vector<uint8_t> grey(size_t(width) * height * 4, 255);
    for (size_t i = 0; i < size_t(width) * height; ++i)
        for (int c = 0; c < 3; ++c)
            grey[i * 4 + size_t(c)] =
                uint8_t(std::lround(255.0f * std::clamp(rgba[i * 4 + 3], 0.0f, 1.0f)));
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/ribbon_edges";
    ASSERT_TRUE(render::ensureOutputDirectory(dir).ok());
    ASSERT_TRUE(render::writePng(dir + "/" + name, width, height, grey).ok());
}

// The picture's edge along a path: at stations every 2 pixels along `path` (screen pixels), the
// place nearest to the path within `reach` pixels along the path's normal where the alpha falls
// through 0.5 going outwards (towards `outward`), as a signed offset from the path (sub-pixel, by
// linear interpolation); nothing where there is none (the path is not on the drawn shape's
// outline there: inside it, or away from it). Returns (arc length, offset) pairs.
std::vector<glm::vec2> edgeAlong(const std::vector<float>& rgba, uint32_t width, uint32_t height,
                                 const std::vector<glm::vec2>& path,
                                 const std::vector<glm::vec2>& outward, float reach) {
    std::vector<glm::vec2> out;
    float s = 0.0f;
    for (size_t i = 0; i + 1 < path.size(); ++i) {
        const glm::vec2 a = path[i], b = path[i + 1];
        const float length = glm::distance(a, b);
        if (length < 1e-4f) continue;
        const glm::vec2 along = (b - a) / length;
        glm::vec2 normal(-along.y, along.x);
        if (glm::dot(normal, outward[i] + outward[i + 1]) < 0.0f) normal = -normal;
        for (float t = std::fmod(2.0f - std::fmod(s, 2.0f), 2.0f); t < length; t += 2.0f) {
            const glm::vec2 p = a + along * t;
            std::optional<float> edge;
            float previous = alphaAt(rgba, width, height, p - normal * reach);
            for (float d = -reach + 0.25f; d <= reach; d += 0.25f) {
                const float here = alphaAt(rgba, width, height, p + normal * d);
                if (previous >= 0.5f && here < 0.5f) { // inside to outside
                    const float at = d - 0.25f + 0.25f * (previous - 0.5f) / (previous - here);
                    if (!edge || std::abs(at) < std::abs(*edge)) edge = at;
                }
                previous = here;
            }
            if (edge) out.emplace_back(s + t, *edge);
        }
        s += length;
    }
    return out;
}

// How far the edge strays from a smooth curve: at each station, the residual of a least-squares
// quadratic in arc length over the stations within `window` pixels of it; the largest, over the
// stations at least `window` from either end.
float edgeDeviation(const std::vector<glm::vec2>& edge, float window) {
    if (edge.empty()) return 0.0f;
    float worst = 0.0f;
    const float first = edge.front().x, last = edge.back().x;
    for (const glm::vec2& centre : edge) {
        if (centre.x - first < window || last - centre.x < window) continue;
        // Normal equations of e = c0 + c1 u + c2 u^2, u = (s - centre) / window.
        glm::dmat3 m(0.0);
        glm::dvec3 r(0.0);
        for (const glm::vec2& p : edge) {
            const double u = (p.x - centre.x) / window;
            if (std::abs(u) > 1.0) continue;
            const glm::dvec3 basis(1.0, u, u * u);
            m += glm::outerProduct(basis, basis);
            r += basis * double(p.y);
        }
        const glm::dvec3 c = glm::inverse(m) * r;
        worst = std::max(worst, float(std::abs(double(centre.y) - c.x)));
    }
    return worst;
}

// --- Joins: a line that turns between two frames -----------------------------------------------

// The moving point on a path that runs along +x and turns by `turn` radians at t = 1 s (frame 30
// at 30 fps), 4.5 m a second; the scene's camera looks at the turn from +z.
anim::Character turningPoint(float turn) {
    anim::Character c = movingPoint();
    anim::Channel& ch = c.clips[0].channels[0];
    const glm::vec3 corner(0.0f, 0.6f, 0.0f);
    const glm::vec3 start = corner - glm::vec3(4.5f, 0, 0);
    const glm::vec3 end = corner + 4.5f * glm::vec3(std::cos(turn), std::sin(turn), 0.0f);
    ch.times = {0.0f, 1.0f, 2.0f};
    ch.values = {glm::vec4(start, 0.0f), glm::vec4(corner, 0.0f), glm::vec4(end, 0.0f)};
    return c;
}

// The ribbon of a wide, even, camera-facing line over that turn, 3 frames after it (six pieces a
// frame: 2 sub-samples, 7.5 cm each).
using RibbonJoinsTest = GpuTest;

TEST_F(RibbonJoinsTest, TheOuterEdgeContinuesAcrossTheWeldBetweenTwoFrames) {
    gpu::Context& ctx = this->ctx();
    const float turn = 1.5707963f; // a right angle
    Result<scene::Scene> s = scene::parseScene(
        R"({"camera": {"position": [0.2, 0.8, 2], "target": [0.2, 0.8, 0], "fov_degrees": 40},
            "output": {"width": 480, "height": 270, "fps": 30, "frames": 34},
            "effects": [{"type": "speed_lines", "lifetime": 6, "stride": 1, "width": 0.2,
                         "sub_samples": 2, "alpha_start": 1, "alpha_end": 1, "core": 0,
                         "colour_over_life": [{"at": 0, "colour": [1, 1, 1, 1]},
                                              {"at": 1, "colour": [1, 1, 1, 1]}],
                         "width_over_life": [{"at": 0, "width": 1}, {"at": 1, "width": 1}]}]})",
        "turn.json");
    ASSERT_TRUE(s) << s.error().message;
    const anim::Character point = turningPoint(turn);
    auto sim = sim::SceneSimulation::create(ctx, s.value(), point);
    ASSERT_TRUE(sim) << sim.error().message;
    const uint32_t width = 480, height = 270;
    render::BakeRenderer renderer(ctx, *sim.value(), width, height, false, VK_SAMPLE_COUNT_1_BIT);
    renderer.setCamera(render::makeCamera(sim.value()->scene().camera, float(width) / height));
    for (uint32_t f = 0; f < sim.value()->frameCount(); ++f)
        gpu::submitOneShot(ctx,
                           [&](VkCommandBuffer cmd) { renderer.record(cmd, *sim.value(), f); });
    // The effects alone over transparent black (one sample a pixel): the alpha is the ribbon's
    // coverage.
    const std::vector<float> coverage = render::readLinearColor(ctx, renderer.layer());
    writeAlpha("turn.png", coverage, width, height);
    // The path's outer side is to the right of it going along (the line turns left). A flat
    // ribbon's alpha falls as 1 - across^2 towards its edges (effect_lines.frag), so its 0.5
    // contour runs at sqrt(0.5) of the half width from the path: on the straight runs, and at the
    // corner, where both pieces end across the bisector, along the bisector. Each piece ending
    // across its own direction would leave a notch there instead, reaching nowhere near it.
    const render::SceneCamera& camera = renderer.camera();
    auto pixel = [&](glm::vec3 w) {
        const glm::vec4 clip = camera.viewProjection * glm::vec4(w, 1.0f);
        return glm::vec2((clip.x / clip.w * 0.5f + 0.5f) * float(width),
                         (0.5f - clip.y / clip.w * 0.5f) * float(height));
    };
    const glm::vec3 corner(0.0f, 0.6f, 0.0f);
    const glm::vec3 bisector =
        glm::normalize(glm::vec3(std::sin(turn / 2), -std::cos(turn / 2), 0));
    const glm::vec2 c = pixel(corner);
    const glm::vec2 outward = glm::normalize(pixel(corner + 0.1f * bisector) - c);
    float reached = 0.0f; // pixels from the corner along the bisector
    for (float d = 0.0f; d < 60.0f; d += 0.25f)
        if (alphaAt(coverage, width, height, c + outward * d) >= 0.5f) reached = d;
    const float perMetre = glm::distance(pixel(corner + 0.1f * bisector), c) / 0.1f;
    const float contour = std::sqrt(0.5f);
    const float expected = contour * 0.1f * perMetre;
    std::printf("corner reach along the bisector: %.2f px (expected %.2f px)\n", double(reached),
                double(expected));
    // Within 1.5 px: the bisector runs along a pixel diagonal, sampled every 0.25 px between pixel
    // centres (a notch would leave it short by the whole 13 px).
    EXPECT_NEAR(reached, expected, 1.5f);

    // The outer edge along the path, on both sides of the corner: one curve (a straight line, a
    // bevelled corner, a straight line), no step where the segments meet.
    std::vector<glm::vec2> path, out;
    for (float u = -0.4f; u <= 0.4f + 1e-6f; u += 0.01f) {
        const glm::vec3 along =
            u < 0.0f ? glm::vec3(1, 0, 0) : glm::vec3(std::cos(turn), std::sin(turn), 0.0f);
        const glm::vec3 w = corner + std::abs(u) * along * (u < 0.0f ? -1.0f : 1.0f);
        path.push_back(pixel(w));
        out.push_back(outward);
    }
    const std::vector<glm::vec2> edge = edgeAlong(coverage, width, height, path, out, 40.0f);
    ASSERT_GT(edge.size(), 20u);
    // Away from the corner the edge is half the width out, on both straight runs.
    for (const glm::vec2& e : edge) {
        const float fromCorner = std::abs(e.x - glm::distance(path.front(), c));
        if (fromCorner > 0.15f * perMetre) {
            EXPECT_NEAR(e.y, contour * 0.1f * perMetre, 1.0f)
                << "at " << e.x << " px along the path";
        }
    }
}

// --- Sheets: the two lines ---------------------------------------------------------------------

// The fighter's sword spans from the grip, by the hand it hangs from, to the tip, 0.95 m out.
TEST(SheetEnds, AreTheVerticesNearestToAndFarthestFromTheJointTheyHangFrom) {
    const anim::Character fighter = anim::makeFighter();
    trajectory::Selection sword;
    sword.meshes = {"sword"};
    const Result<trajectory::Source> all = trajectory::selectSource(fighter, sword);
    ASSERT_TRUE(all) << all.error().message;
    const Result<trajectory::Source> ends = trajectory::twoEnds(fighter, all.value());
    ASSERT_TRUE(ends) << ends.error().message;
    ASSERT_EQ(ends.value().vertices.size(), 2u);
    const anim::Pose rest = anim::samplePose(fighter, nullptr, 0.0f);
    int hand = -1;
    for (size_t n = 0; n < fighter.nodes.size(); ++n)
        if (fighter.nodes[n].name == "hand_r") hand = int(n);
    ASSERT_GE(hand, 0);
    const glm::vec3 at = glm::vec3(rest.world[size_t(hand)][3]);
    const std::vector<anim::DualQuatJoint> palette =
        trajectory::sourcePalette(fighter, ends.value(), rest);
    float distance[2];
    for (int i = 0; i < 2; ++i) {
        const shared::SkinVertexIn& v = ends.value().vertices[size_t(i)];
        distance[i] = glm::distance(anim::skinDualQuat(palette, glm::vec3(v.position),
                                                       glm::vec3(v.normal), v.joints, v.weights)
                                        .position,
                                    at);
    }
    std::printf("sheet ends: %.3f m and %.3f m from the hand\n", double(distance[0]),
                double(distance[1]));
    EXPECT_LT(distance[0], 0.1f); // at the grip
    EXPECT_GT(distance[1], 0.9f); // the blade's tip
}

TEST(SheetEnds, RefuseVerticesAllAsFarFromTheJoint) {
    const anim::Character point = movingPoint(); // one vertex
    const Result<trajectory::Source> all = trajectory::selectSource(point, {});
    ASSERT_TRUE(all) << all.error().message;
    const Result<trajectory::Source> ends = trajectory::twoEnds(point, all.value());
    ASSERT_FALSE(ends);
    EXPECT_NE(ends.error().message.find("a sheet needs bound vertices at different distances"),
              std::string::npos)
        << ends.error().message;
}

// --- The hero's slash arc ----------------------------------------------------------------------

// The hero scene with only its slash arc, drawn as `shape` with the keys `keys` changed.
scene::Scene heroSlash(const std::string& keys) {
    Result<scene::Scene> hero =
        scene::loadScene(std::string(MFX_SOURCE_DIR) + "/docs/scenes/hero.json");
    EXPECT_TRUE(hero) << hero.error().message;
    scene::Scene s = hero.value();
    std::vector<scene::EffectSpec> kept;
    for (const scene::EffectSpec& e : s.effects)
        if (e.name == "slash arc") kept.push_back(e);
    EXPECT_EQ(kept.size(), 1u);
    s.effects = kept;
    if (!keys.empty()) {
        // The slash arc's own keys over the scene file's, through the parser.
        Result<scene::Scene> changed = scene::parseScene(
            R"({"character": {"source": "fighter", "clip": "kick_slash"},
                "effects": [{"type": "speed_lines", "name": "slash arc", "meshes": ["sword"],
                             "start": 1.0, )" +
                keys + "}]}",
            "slash.json");
        EXPECT_TRUE(changed) << changed.error().message;
        s.effects = changed.value().effects;
    }
    return s;
}

// The slash arc at frame 40 drawn alone at 1920x1080 through the scene's camera (RGBA, linear,
// premultiplied). Drawn alpha-blended at full strength along each segment (alpha_end 1): the
// measure reads the drawn coverage (alpha), which an additive blend leaves at 0, and sees the
// geometry rather than each frame's segment fading along its length.
std::vector<float> drawSlash(gpu::Context& ctx, scene::Scene s) {
    const uint32_t width = 1920, height = 1080, frame = 40;
    auto* lines = s.effects.at(0).as<scene::SpeedLinesSpec>();
    lines->ribbon.additive = false;
    lines->trail.alphaEnd = 1.0f;
    const Result<anim::Character> character = scene::loadCharacter(s);
    EXPECT_TRUE(character) << character.error().message;
    auto sim = sim::SceneSimulation::create(ctx, s, character.value());
    EXPECT_TRUE(sim) << sim.error().message;
    render::BakeRenderer renderer(ctx, *sim.value(), width, height, false);
    renderer.setCamera(render::makeCamera(sim.value()->scene().camera, float(width) / height));
    for (uint32_t f = 0; f <= frame; ++f)
        gpu::submitOneShot(ctx,
                           [&](VkCommandBuffer cmd) { renderer.record(cmd, *sim.value(), f); });
    return render::readLinearColor(ctx, renderer.layer());
}

// The outline of the drawn shape seen from above (`fromTop`) or below, column by column over
// columns [x0, x1]: the first row, coming from that side, where the alpha rises through 0.5
// (sub-pixel, by linear interpolation along the column). Returns (column, row) pairs.
std::vector<glm::vec2> outline(const std::vector<float>& rgba, uint32_t width, uint32_t height,
                               int x0, int x1, bool fromTop) {
    std::vector<glm::vec2> out;
    for (int x = std::max(x0, 0); x <= std::min(x1, int(width) - 1); ++x) {
        auto a = [&](int y) { return rgba[(size_t(y) * width + size_t(x)) * 4 + 3]; };
        const int step = fromTop ? 1 : -1;
        for (int y = fromTop ? 1 : int(height) - 2; y >= 0 && y < int(height); y += step) {
            const float before = a(y - step), here = a(y);
            if (before < 0.5f && here >= 0.5f) {
                out.emplace_back(float(x),
                                 float(y - step) + float(step) * (0.5f - before) / (here - before));
                break;
            }
        }
    }
    return out;
}

// The last column the shape reaches (alpha 0.5 or more), from the left; -1 if none.
int lastColumn(const std::vector<float>& rgba, uint32_t width, uint32_t height) {
    for (int x = int(width) - 1; x >= 0; --x)
        for (uint32_t y = 0; y < height; ++y)
            if (rgba[(size_t(y) * width + size_t(x)) * 4 + 3] >= 0.5f) return x;
    return -1;
}

// The ribbons it was drawn with before: one for each third vertex of the sword, each lying in the
// plane of its own vertex's surface, 5 cm wide, fading along each frame's segment.
const char* kSlashAsRibbons =
    R"("stride": 3, "lifetime": 7, "sub_samples": 6, "width": 0.05, "facing": "blade",
       "intensity": 1.2, "blend": "additive", "core": 0.5,
       "colour_over_life": [{"at": 0, "colour": [0.85, 0.95, 1, 1]},
                            {"at": 0.25, "colour": [0.35, 0.7, 1, 0.85]},
                            {"at": 1, "colour": [0.1, 0.25, 1, 0]}],
       "width_over_life": [{"at": 0, "width": 1}, {"at": 0.25, "width": 0.9},
                           {"at": 1, "width": 0}])";

using SlashEdgeTest = GpuTest;

TEST_F(SlashEdgeTest, TheHeroSlashArcsOuterEdgeIsOneSmoothCurveAt1920x1080) {
    gpu::Context& ctx = this->ctx();
    const scene::Scene sheet = heroSlash("");
    ASSERT_TRUE(sheet.effects.at(0).as<scene::SpeedLinesSpec>()->ribbon.sheet)
        << "the hero's slash arc is a sheet";
    const uint32_t width = 1920, height = 1080;
    const float window = 24.0f; // pixels on each side
    // The arm of the arc reaching out to the sword's tip at frame 40 (the right of the picture):
    // its outline from above (the outer edge, where the ribbons' stairs were) and from below,
    // over the 220 columns before its end.
    struct Measured {
        float upper, lower;
        size_t columns;
    };
    auto measure = [&](const std::vector<float>& rgba, const char* name) {
        writeAlpha(name, rgba, width, height);
        const int end = lastColumn(rgba, width, height);
        EXPECT_GT(end, int(width) / 2) << name;
        const std::vector<glm::vec2> upper = outline(rgba, width, height, end - 220, end - 8, true);
        const std::vector<glm::vec2> lower =
            outline(rgba, width, height, end - 220, end - 8, false);
        return Measured{edgeDeviation(upper, window), edgeDeviation(lower, window),
                        std::min(upper.size(), lower.size())};
    };
    const Measured after = measure(drawSlash(ctx, sheet), "slash_sheet.png");
    const Measured before =
        measure(drawSlash(ctx, heroSlash(kSlashAsRibbons)), "slash_ribbons.png");
    std::printf("slash arc, frame 40, 1920x1080, the arm's last 212 columns: largest distance of "
                "its outline from a smooth curve (quadratic over +-%.0f px), above / below: "
                "sheet %.2f / %.2f px; the ribbons as before %.2f / %.2f px\n",
                double(window), double(after.upper), double(after.lower), double(before.upper),
                double(before.lower));
    ASSERT_GE(after.columns, 200u);
    ASSERT_GE(before.columns, 200u);
    EXPECT_LE(after.upper, 1.0f);
    EXPECT_LE(after.lower, 1.0f);
    // The measure sees the stairs the ribbons left.
    EXPECT_GT(before.upper, 2.0f);
}

} // namespace
} // namespace mfx::test
