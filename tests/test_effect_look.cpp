// How the effects look (scene::RibbonLook, scene::VolumeLook; shaders/render/ribbon_style.glsl,
// effect_lines.*, effect_particles.*, effect_volume.*, depth_fade.glsl). The speed-lines' ribbons:
// the keys, the gradient and curve between their stops, and on the GPU a straight ribbon (one point
// sliding along +x at 1.5 m/s, seen from the side) whose colour at its head and tail is the
// gradient's end stops and whose width follows width_over_life along it; facing, tubes, the
// afterimage's lines; the particles' share of the look (their size and colour over life); the depth
// fade; and the lit volumes' colour over life and Fresnel rim.
#include "core/scene/kinds/afterimage_effect.h"
#include "core/scene/kinds/silhouette_shell_effect.h"
#include "core/scene/kinds/swept_volume_effect.h"
#include "core/scene/kinds/trail_effects.h"
#include "render/frame_renderer.h"
#include "tests/gpu_test.h"
#include "tests/moving_point.h"
#include "tests/scene_render_util.h"

#include <cmath>
#include <optional>

namespace mfx::test {
namespace {

// The point sliding along x, seen from the side, with one effect: speed-lines with `look`, or
// the JSON of `effect`, seen from `eye`. No bloom: the tests read the linear picture, whose light
// it would spread.
Result<scene::Scene> pointScene(const std::string& effect, const std::string& eye = "0, 0.6, 2") {
    return scene::parseScene(R"({
        "character": {"source": "point.gltf"},
        "stage": {"floor": false, "backdrop": false},
        "lights": [{"direction": [0, -1, 0], "shadow": false}],
        "camera": {"position": [)" +
                                 eye + R"(], "target": [0, 0.6, 0], "fov_degrees": 40},
        "output": {"fps": 30, "frames": 36}, "post": {"bloom": 0},
        "effects": [)" + effect + "]}",
                             "ribbon.json");
}

Result<scene::Scene> lineScene(const std::string& look) {
    return pointScene(R"({"type": "speed_lines", "lifetime": 10, "stride": 1, "width": 0.2,
                          "alpha_start": 1, "alpha_end": 1, "core": 0, )" +
                      look + "}");
}

const scene::SpeedLinesSpec& linesOf(const scene::Scene& s) {
    return *s.effects.at(0).as<scene::SpeedLinesSpec>();
}

TEST(RibbonLook, ReadsEveryKey) {
    Result<scene::Scene> s = lineScene(R"("colour_over_life": [
            {"at": 0, "colour": [1, 0.9, 0.5, 1]}, {"at": 0.3, "colour": [1, 0.3, 0]},
            {"at": 1, "colour": [0.2, 0, 0.5, 0]}],
        "width_over_life": [{"at": 0, "width": 1}, {"at": 1, "width": 0.25}],
        "intensity": 6, "blend": "additive")");
    ASSERT_TRUE(s) << s.error().message;
    const scene::RibbonLook& r = linesOf(s.value()).ribbon;
    ASSERT_EQ(r.colourOverLife.size(), 3u);
    EXPECT_FLOAT_EQ(r.colourOverLife[1].at, 0.3f);
    EXPECT_EQ(r.colourOverLife[1].colour, glm::vec4(1.0f, 0.3f, 0.0f, 1.0f));
    ASSERT_EQ(r.widthOverLife.size(), 2u);
    EXPECT_FLOAT_EQ(r.widthOverLife[1].value, 0.25f);
    EXPECT_FLOAT_EQ(r.intensity, 6.0f);
    EXPECT_TRUE(r.additive);
    EXPECT_FLOAT_EQ(r.core, 0.0f);
    EXPECT_FALSE(r.bladeFacing);
    EXPECT_FALSE(r.tube);
    Result<scene::Scene> shaped = lineScene(R"("facing": "blade", "shape": "tube")");
    ASSERT_TRUE(shaped) << shaped.error().message;
    EXPECT_TRUE(linesOf(shaped.value()).ribbon.bladeFacing);
    EXPECT_TRUE(linesOf(shaped.value()).ribbon.tube);
}

TEST(RibbonLook, RefusesBadStops) {
    const std::pair<const char*, const char*> cases[] = {
        {R"("colour_over_life": [{"at": 0, "colour": [1, 0, 0]}])",
         "effects[0].colour_over_life: expected an array of 2 to 8 objects, got an array of 1"},
        {R"("width_over_life": [{"at": 0.5, "width": 1}, {"at": 0.2, "width": 2}])",
         "effects[0].width_over_life[1].at: 0.2 is before the previous stop's 0.5"},
        {R"("width_over_life": [{"width": 1}, {"at": 1, "width": 2}])",
         "effects[0].width_over_life[0].at: missing"},
        {R"("colour_over_life": [{"at": 0, "color": [1, 0, 0]}, {"at": 1, "colour": [1, 0, 0]}])",
         "effects[0].colour_over_life[0].color: unknown key; keys here are: at, colour"},
        {R"("blend": "screen")", "effects[0].blend: \"screen\" is not one of: alpha, additive"},
        {R"("intensity": -1)", "effects[0].intensity: -1 is outside [0, 1000]"},
        {R"("facing": "view")", "effects[0].facing: \"view\" is not one of: camera, blade"},
        {R"("shape": "cylinder")", "effects[0].shape: \"cylinder\" is not one of: flat, tube"},
    };
    for (const auto& [look, message] : cases) {
        Result<scene::Scene> s = lineScene(look);
        ASSERT_FALSE(s) << look;
        EXPECT_NE(s.error().message.find(message), std::string::npos) << s.error().message;
    }
}

TEST(RibbonLook, GradientAndCurveAreLinearBetweenStops) {
    const std::vector<scene::GradientStop> colours = {{0.0f, glm::vec4(1, 0, 0, 1)},
                                                      {0.5f, glm::vec4(0, 1, 0, 1)},
                                                      {1.0f, glm::vec4(0, 0, 1, 0)}};
    EXPECT_EQ(scene::colourAt(colours, 0.0f), glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(scene::colourAt(colours, 0.25f), glm::vec4(0.5f, 0.5f, 0, 1));
    EXPECT_EQ(scene::colourAt(colours, 1.0f), glm::vec4(0, 0, 1, 0));
    const std::vector<scene::CurveStop> widths = {{0.2f, 2.0f}, {0.6f, 1.0f}};
    EXPECT_FLOAT_EQ(scene::valueAt(widths, 0.0f), 2.0f); // held before the first stop
    EXPECT_FLOAT_EQ(scene::valueAt(widths, 0.4f), 1.5f);
    EXPECT_FLOAT_EQ(scene::valueAt(widths, 0.9f), 1.0f); // and after the last
}

class RibbonDrawTest : public GpuTest {
protected:
    static constexpr uint32_t kWidth = 512, kHeight = 256;

    // The last frame's linear colour (RGBA floats), the point's head at x = 0.25, its trail of 10
    // frames (0.5 m) back to x = -0.25, at y = 0.6 (the picture's middle row).
    // `normal`: the point's surface normal (what a blade-facing ribbon lies across).
    std::vector<float> drawLine(const std::string& look, glm::vec3 normal = {0, 1, 0}) {
        return draw(lineScene(look), normal);
    }
    // With `triangle` > 0, the point is a triangle that many metres across (the afterimage and the
    // motion volumes draw from triangles). With `extra`, a second vertex at that offset from the
    // point (on the same joint).
    std::vector<float> draw(const Result<scene::Scene>& s, glm::vec3 normal, float triangle = 0.0f,
                            std::optional<glm::vec3> extra = std::nullopt) {
        EXPECT_TRUE(s) << (s ? "" : s.error().message);
        anim::Character point = movingPoint();
        anim::Primitive& p = point.meshes[0].primitives[0];
        p.normals[0] = normal;
        if (triangle) {
            p.positions = {glm::vec3(0.0f), glm::vec3(0, triangle, 0), glm::vec3(0, 0, triangle)};
            p.normals.assign(3, normal);
            p.joints.assign(3, glm::uvec4(0));
            p.weights.assign(3, glm::vec4(1, 0, 0, 0));
            p.indices = {0, 1, 2};
        }
        if (extra) {
            p.positions.push_back(*extra);
            p.normals.push_back(normal);
            p.joints.push_back(glm::uvec4(0));
            p.weights.push_back(glm::vec4(1, 0, 0, 0));
        }
        auto sim = sim::SceneSimulation::create(ctx(), s.value(), point);
        EXPECT_TRUE(sim) << (sim ? "" : sim.error().message);
        render::FrameRenderer renderer(ctx(), *sim.value(), kWidth, kHeight, samples_);
        playFrames(ctx(), renderer, *sim.value(), 0, sim.value()->frameCount());
        camera_ = renderer.camera();
        return render::readLinearColor(ctx(), renderer.sceneTarget());
    }
    // The pixel column of world x on the line's row.
    float column(float x) const {
        const glm::vec4 clip = camera_.viewProjection * glm::vec4(x, 0.6f, 0.0f, 1.0f);
        return (clip.x / clip.w * 0.5f + 0.5f) * float(kWidth);
    }
    // The pixel (column, row from the top) of world point `w`.
    glm::ivec2 pixel(glm::vec3 w) const {
        const glm::vec4 clip = camera_.viewProjection * glm::vec4(w, 1.0f);
        return {int((clip.x / clip.w * 0.5f + 0.5f) * float(kWidth)),
                int((0.5f - clip.y / clip.w * 0.5f) * float(kHeight))};
    }
    static glm::vec4 at(const std::vector<float>& rgba, int x, int y) {
        const size_t p = (size_t(y) * kWidth + size_t(x)) * 4;
        return {rgba[p], rgba[p + 1], rgba[p + 2], rgba[p + 3]};
    }
    // Rows in column x the ribbon changes (against the background, the column's top pixel).
    static int coveredRows(const std::vector<float>& rgba, int x) {
        const glm::vec4 background = at(rgba, x, 0);
        int rows = 0;
        for (uint32_t y = 0; y < kHeight; ++y) {
            const glm::vec4 d = glm::abs(at(rgba, x, int(y)) - background);
            rows += d.r + d.g + d.b > 0.004f ? 1 : 0;
        }
        return rows;
    }
    render::SceneCamera camera_;
    VkSampleCountFlagBits samples_ = VK_SAMPLE_COUNT_1_BIT;
    // The full width all along (no taper).
    inline static const std::string kEvenWidth =
        R"("width_over_life": [{"at": 0, "width": 1}, {"at": 1, "width": 1}], )";
    static constexpr float kHead = 0.25f, kTail = -0.25f;
};

TEST_F(RibbonDrawTest, HeadAndTailTakeTheGradientsEndStops) {
    const std::vector<float> rgba = drawLine(R"("colour_over_life": [
        {"at": 0, "colour": [1, 0.5, 0, 1]}, {"at": 1, "colour": [0, 0.2, 1, 1]}])");
    const int row = int(kHeight / 2);
    const float head = column(kHead), tail = column(kTail);
    ASSERT_GT(head - tail, 60.0f); // 0.5 m at 176 pixels a metre
    // Two pixels inside each end: u is 2 / (head - tail) from 0 or 1.
    const glm::vec4 atHead = at(rgba, int(head) - 2, row);
    const glm::vec4 atTail = at(rgba, int(tail) + 2, row);
    const float u = 2.5f / (head - tail);
    const glm::vec4 expectHead = glm::mix(glm::vec4(1, 0.5f, 0, 1), glm::vec4(0, 0.2f, 1, 1), u);
    const glm::vec4 expectTail =
        glm::mix(glm::vec4(1, 0.5f, 0, 1), glm::vec4(0, 0.2f, 1, 1), 1.0f - u);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(atHead[c], expectHead[c], 0.03f) << "head, channel " << c;
        EXPECT_NEAR(atTail[c], expectTail[c], 0.03f) << "tail, channel " << c;
    }
}

TEST_F(RibbonDrawTest, WidthFollowsItsCurveAlongTheRibbon) {
    const std::vector<float> rgba =
        drawLine(R"("width_over_life": [{"at": 0, "width": 1}, {"at": 1, "width": 0.4}])");
    const float head = column(kHead), tail = column(kTail);
    // Pixels per metre at the line's depth: the 0.2 m width at the head.
    const float perMetre = (head - tail) / (kHead - kTail);
    for (float u : {0.1f, 0.3f, 0.5f, 0.7f, 0.9f}) {
        const int x = int(std::lround(head - u * (head - tail)));
        const float expected = 0.2f * (1.0f - 0.6f * u) * perMetre;
        const int rows = coveredRows(rgba, x);
        std::cout << "u " << u << ": " << rows << " rows, expected " << expected << "\n";
        EXPECT_NEAR(float(rows), expected, 1.5f) << "at u = " << u << ", column " << x;
    }
}

// Intensity 4 of orange: light above 1 on the ribbon. Additive keeps the background's blue
// behind it (adds), the alpha blend covers it.
TEST_F(RibbonDrawTest, AdditiveRibbonsAddHdrLight) {
    const std::string orange = R"("colour_over_life": [
        {"at": 0, "colour": [1, 0.5, 0, 1]}, {"at": 1, "colour": [1, 0.5, 0, 1]}],
        "intensity": 4, )";
    const std::vector<float> added = drawLine(orange + R"("blend": "additive")");
    const std::vector<float> covered = drawLine(orange + R"("blend": "alpha")");
    const int x = int(column(0.0f)), y = int(kHeight / 2);
    const glm::vec4 background = at(added, x, 0), a = at(added, x, y), c = at(covered, x, y);
    std::cout << "background blue " << background.b << "; ribbon middle, additive: " << a.r << " "
              << a.g << " " << a.b << "; alpha: " << c.r << " " << c.g << " " << c.b << "\n";
    const float coverage = (a.r - background.r) / 4.0f; // the soft edge's alpha at this row
    EXPECT_GT(coverage, 0.9f);
    EXPECT_GT(a.r, 3.6f) << "HDR light";
    EXPECT_NEAR(a.g - background.g, 2.0f * coverage, 0.02f) << "orange, as given";
    EXPECT_NEAR(a.b, background.b, 0.002f) << "additive: the background still shows";
    EXPECT_LT(c.b, background.b * (1.0f - coverage) + 0.002f) << "alpha: the ribbon covers it";
}

// Facing the blade, the ribbon lies in the plane of the point's surface through its motion: with
// the normal towards the camera it is as wide as a camera-facing one; with the normal up (the
// motion plane seen edge-on from the side) it all but vanishes, where the camera-facing one stays.
TEST_F(RibbonDrawTest, BladeFacingLiesInTheSurfacesPlane) {
    const int x = int(column(0.0f));
    const int facing = coveredRows(drawLine(kEvenWidth + R"("facing": "camera")", {0, 1, 0}), x);
    const int bladeToCamera =
        coveredRows(drawLine(kEvenWidth + R"("facing": "blade")", {0, 0, 1}), x);
    const int bladeEdgeOn =
        coveredRows(drawLine(kEvenWidth + R"("facing": "blade")", {0, 1, 0}), x);
    std::cout << "rows: camera-facing " << facing << ", blade facing the camera " << bladeToCamera
              << ", blade seen edge-on " << bladeEdgeOn << "\n";
    EXPECT_GT(facing, 10);
    EXPECT_NEAR(bladeToCamera, facing, 1);
    EXPECT_LE(bladeEdgeOn, 2);
}

// A sheet joins the point's line and its second vertex's, 0.3 m above it (the one farther from
// the joint: the outer edge), into one surface reaching `width` in from the outer edge: 0.2 m,
// from 0.9 down to 0.7, not to the point's own line at 0.6.
TEST_F(RibbonDrawTest, SheetReachesItsWidthInFromTheOuterLine) {
    const std::vector<float> rgba =
        draw(lineScene(kEvenWidth + R"("shape": "sheet")"), {0, 0, 1}, 0.0f, glm::vec3(0, 0.3f, 0));
    const int x = int(std::lround(column(0.0f)));
    const glm::vec4 background = at(rgba, x, 0);
    int top = -1, bottom = -1;
    for (int y = 0; y < int(kHeight); ++y) {
        const glm::vec4 d = glm::abs(at(rgba, x, y) - background);
        if (d.r + d.g + d.b > 0.004f) {
            if (top < 0) top = y;
            bottom = y;
        }
    }
    const int outer = pixel({0.0f, 0.9f, 0.0f}).y, reach = pixel({0.0f, 0.7f, 0.0f}).y;
    std::cout << "sheet rows " << top << " to " << bottom << "; outer line at " << outer
              << ", reach at " << reach << "\n";
    EXPECT_NEAR(top, outer, 1);
    EXPECT_NEAR(bottom, reach, 2); // its alpha fades to 0 at the inner edge
    // Opaque at the outer edge, fading inwards.
    EXPECT_GT(at(rgba, x, outer + 1).r, at(rgba, x, (outer + reach) / 2).r);
}

TEST(RibbonLook, SheetsAreSpeedLinesOnly) {
    Result<scene::Scene> s = lineScene(R"("shape": "sheet")");
    ASSERT_TRUE(s) << s.error().message;
    EXPECT_TRUE(linesOf(s.value()).ribbon.sheet);
    EXPECT_TRUE(linesOf(s.value()).trail.twoEnds);
    Result<scene::Scene> afterimage =
        pointScene(R"({"type": "afterimage_smear", "variant": "speed_lines", "shape": "sheet"})");
    ASSERT_FALSE(afterimage);
    EXPECT_NE(
        afterimage.error().message.find("effects[0].shape: \"sheet\" is not one of: flat, tube"),
        std::string::npos)
        << afterimage.error().message;
}

// A tube is as wide on the screen as the flat ribbon whatever the normal, and lit by the key light
// from above: brighter above its axis than below, where the flat ribbon is the same both sides.
TEST_F(RibbonDrawTest, TubeKeepsItsWidthAndIsLitFromAbove) {
    const std::string white = std::string(R"("colour_over_life": [
        {"at": 0, "colour": [1, 1, 1, 1]}, {"at": 1, "colour": [1, 1, 1, 1]}], )") +
                              kEvenWidth;
    const int x = int(column(0.0f)), row = int(kHeight / 2);
    const std::vector<float> flat = drawLine(white + R"("shape": "flat")");
    const std::vector<float> tube = drawLine(white + R"("shape": "tube", "facing": "blade")");
    const std::vector<float> tubeEdgeOn =
        drawLine(white + R"("shape": "tube", "facing": "blade")", {0, 0, 1});
    const int flatRows = coveredRows(flat, x);
    std::cout << "rows: flat " << flatRows << ", tube " << coveredRows(tube, x)
              << ", tube with the normal to the camera " << coveredRows(tubeEdgeOn, x) << "\n";
    EXPECT_NEAR(coveredRows(tube, x), flatRows, 1);
    EXPECT_NEAR(coveredRows(tubeEdgeOn, x), flatRows, 1);
    const int quarter = flatRows / 4;
    auto luminance = [&](const std::vector<float>& rgba, int y) {
        const glm::vec4 c = at(rgba, x, y);
        return c.r + c.g + c.b;
    };
    // Row 0 is the picture's top; the axis runs between rows row - 1 and row.
    const int above = row - 1 - quarter, below = row + quarter;
    const float tubeAbove = luminance(tube, above), tubeBelow = luminance(tube, below);
    const float flatAbove = luminance(flat, above), flatBelow = luminance(flat, below);
    std::cout << "background " << luminance(flat, above - quarter * 3) << " / "
              << luminance(flat, below + quarter * 3) << "\n";
    std::cout << "a quarter of the width above and below the axis: tube " << tubeAbove << " / "
              << tubeBelow << ", flat " << flatAbove << " / " << flatBelow << "\n";
    EXPECT_GT(tubeAbove, 1.5f * tubeBelow) << "lit from above";
    EXPECT_NEAR(flatAbove, flatBelow, 0.05f * flatAbove) << "the flat ribbon is its own light";
}

// The afterimage's speed-line variant takes the same look, its life running from the mesh (u = 0)
// to the pushed end (u = 1): the point, facing back along its motion, pushed back 6 frames of
// its travel; the line's two ends take the gradient's end stops.
TEST_F(RibbonDrawTest, AfterimageLinesTakeTheGradientFromTheMeshToThePushedEnd) {
    const std::vector<float> rgba = draw(pointScene(R"({"type": "afterimage_smear",
        "variant": "speed_lines", "width": 0.2, "strength_character": 6, "strength_animation": 0,
        "random_min": 1, "random_max": 1, "alpha_end": 1,
        "colour_over_life": [{"at": 0, "colour": [1, 0.5, 0, 1]}, {"at": 1, "colour": [0, 0.2, 1, 1]}],
        "width_over_life": [{"at": 0, "width": 1}, {"at": 1, "width": 1}], "core": 0})"),
                                         {-1, 0, 0}, 0.001f);
    // The covered run of the middle row: the pushed end on the left, the point on the right.
    const int row = int(kHeight / 2);
    const glm::vec4 background = at(rgba, 0, row);
    int first = -1, last = -1;
    for (int x = 0; x < int(kWidth); ++x) {
        const glm::vec4 d = glm::abs(at(rgba, x, row) - background);
        if (d.r + d.g + d.b > 0.01f) {
            if (first < 0) first = x;
            last = x;
        }
    }
    std::cout << "afterimage line from column " << first << " to " << last << "\n";
    ASSERT_GT(last - first, 40) << "a line 6 frames of the point's travel long";
    EXPECT_NEAR(float(last), column(0.25f), 2.0f) << "the line starts at the point";
    const float u = 2.5f / float(last - first);
    const glm::vec4 head = at(rgba, last - 2, row), tail = at(rgba, first + 2, row);
    const glm::vec4 expectHead = glm::mix(glm::vec4(1, 0.5f, 0, 1), glm::vec4(0, 0.2f, 1, 1), u);
    const glm::vec4 expectTail =
        glm::mix(glm::vec4(1, 0.5f, 0, 1), glm::vec4(0, 0.2f, 1, 1), 1.0f - u);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(head[c], expectHead[c], 0.05f) << "at the mesh, channel " << c;
        EXPECT_NEAR(tail[c], expectTail[c], 0.05f) << "at the pushed end, channel " << c;
    }
}

// Depth fade: seen from above, a white ribbon 0.6 m over the floor has the floor a view depth g
// behind it at its centre; with depth_fade f its alpha is scaled by min(g / f, 1), measured as its
// contrast against the floor at that pixel, against the same ribbon with no fade; and the same for
// the point's particles. (A second vertex,
// a metre to the side and 0.6 m lower, puts the floor under the point's path.)
TEST_F(RibbonDrawTest, DepthFadeScalesAlphaByTheGapToTheSurfaceBehind) {
    auto fadedLine = [&](const std::string& type, const std::string& look) {
        Result<scene::Scene> s = scene::parseScene(R"({
            "character": {"source": "point.gltf"},
            "stage": {"floor": true, "backdrop": false},
            "lights": [{"direction": [0, -1, 0], "shadow": false}],
            "camera": {"position": [0, 2.6, 0.5], "target": [0, 0.6, 0], "fov_degrees": 40},
            "output": {"fps": 30, "frames": 36}, "post": {"bloom": 0},
            "effects": [{"type": ")" + type + R"(", "lifetime": 10, "stride": 1,
                "alpha_start": 1, "alpha_end": 1, )" + look +
                                                       R"(,
                "colour_over_life": [{"at": 0, "colour": [1, 1, 1]}, {"at": 1, "colour": [1, 1, 1]}]}]})",
                                                   "fade.json");
        return draw(s, {0, 1, 0}, 0.0f, glm::vec3(0, -0.6f, -1.0f));
    };
    const glm::vec3 eye(0, 2.6f, 0.5f), centre(-0.05f, 0.6f, 0.0f);
    // The floor (y = 0) behind the ribbon's centre, along the ray through it, in view depth.
    const glm::vec3 ray = centre - eye;
    const glm::vec3 floorHit = eye + ray * (eye.y / -ray.y);
    const float gap = glm::dot(floorHit - centre, glm::normalize(glm::vec3(0, 0.6f, 0) - eye));
    // Particles, and lines with one sample and with 4 (where the scene's rendering is resumed
    // over its multisampled images).
    const std::pair<const char*, VkSampleCountFlagBits> cases[] = {
        {"speed_lines", VK_SAMPLE_COUNT_1_BIT},
        {"motion_particles", VK_SAMPLE_COUNT_1_BIT},
        {"speed_lines", VK_SAMPLE_COUNT_4_BIT}};
    for (const auto& [type, samples] : cases) {
        samples_ = samples;
        SCOPED_TRACE(type);
        SCOPED_TRACE(samples_);
        const bool lines = std::string(type) == "speed_lines";
        // Additive: overlapping pieces and sprites add, so the contrast is linear in alpha.
        const std::string size =
            std::string(lines ? R"("width": 0.2, "core": 0)" : R"("size": 0.2)") +
            R"(, "blend": "additive")";
        const std::vector<float> hard = fadedLine(type, size);
        const glm::ivec2 p = pixel(centre);
        // The floor alone at that pixel: the same effect adding no light.
        const glm::vec4 floor = at(fadedLine(type, size + R"(, "intensity": 0)"), p.x, p.y);
        auto contrast = [&](const std::vector<float>& rgba) {
            const glm::vec4 c = at(rgba, p.x, p.y) - floor;
            return c.r + c.g + c.b;
        };
        const float none = contrast(hard);
        for (float fade : {0.3f, 1.2f}) {
            const float ratio =
                contrast(fadedLine(type, size + R"(, "depth_fade": )" + std::to_string(fade))) /
                none;
            const float expected = std::min(gap / fade, 1.0f);
            std::cout << type << ", " << samples_ << " sample(s), gap " << gap << " m, depth_fade "
                      << fade << ": alpha x " << ratio << ", expected " << expected << "\n";
            EXPECT_NEAR(ratio, expected, 0.01f) << "depth_fade " << fade;
        }
    }
}

TEST(ParticleLook, ReadsItsKeysAndRefusesTheRibbonsOwn) {
    Result<scene::Scene> s = pointScene(R"({"type": "motion_particles", "size": 0.1,
        "colour_over_life": [{"at": 0, "colour": [1, 1, 1]}, {"at": 1, "colour": [1, 0, 0, 0]}],
        "size_over_life": [{"at": 0, "size": 1}, {"at": 1, "size": 0.5}],
        "intensity": 3, "blend": "additive"})");
    ASSERT_TRUE(s) << s.error().message;
    const scene::RibbonLook& look = s.value().effects.at(0).as<scene::MotionParticlesSpec>()->look;
    EXPECT_EQ(look.colourOverLife.size(), 2u);
    ASSERT_EQ(look.widthOverLife.size(), 2u);
    EXPECT_FLOAT_EQ(look.widthOverLife[1].value, 0.5f);
    EXPECT_FLOAT_EQ(look.intensity, 3.0f);
    EXPECT_TRUE(look.additive);
    Result<scene::Scene> bad = pointScene(R"({"type": "motion_particles", "shape": "tube"})");
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message.find("effects[0].shape: not a key of motion_particles effects"),
              std::string::npos)
        << bad.error().message;
}

// Particles of the sliding point at 10 fps, one every 0.15 m, living 4 frames: the dots at life
// u = 0, 0.25, 0.5 and 0.75 are size * size_over_life(u) across and, at their centres, the colour
// of colour_over_life(u).
TEST_F(RibbonDrawTest, ParticlesTakeTheirSizeAndColourOverLife) {
    Result<scene::Scene> s = scene::parseScene(R"({
        "character": {"source": "point.gltf"},
        "stage": {"floor": false, "backdrop": false},
        "lights": [{"direction": [0, -1, 0], "shadow": false}],
        "camera": {"position": [0, 0.6, 2], "target": [0, 0.6, 0], "fov_degrees": 40},
        "output": {"fps": 10, "frames": 12}, "post": {"bloom": 0},
        "effects": [{"type": "motion_particles", "lifetime": 4, "stride": 1, "sub_samples": 1,
            "size": 0.12, "alpha_start": 1, "alpha_end": 1,
            "colour_over_life": [{"at": 0, "colour": [1, 0.8, 0.2]}, {"at": 1, "colour": [0.1, 0.3, 1]}],
            "size_over_life": [{"at": 0, "size": 1}, {"at": 1, "size": 0.25}]}]})",
                                               "particles.json");
    const std::vector<float> rgba = draw(s, {0, 1, 0});
    const int row = int(kHeight / 2);
    const glm::vec4 background = at(rgba, 0, 0);
    const float perMetre = column(1.0f) - column(0.0f);
    for (int k = 0; k < 4; ++k) {
        const float u = 0.25f * float(k);
        const float x = 0.15f - 0.15f * float(k); // the head at t = 1.1 s, x = -1.5 + 1.5 t
        const int centre = int(column(x));
        // The dot's own run of covered columns through its centre (its neighbours are apart).
        auto covered = [&](int px) {
            const glm::vec4 d = glm::abs(at(rgba, px, row) - background);
            return d.r + d.g + d.b > 0.004f;
        };
        int left = centre, right = centre;
        while (left > 0 && covered(left - 1))
            --left;
        while (right + 1 < int(kWidth) && covered(right + 1))
            ++right;
        const int columns = covered(centre) ? right - left + 1 : 0;
        const float expected = 0.12f * (1.0f - 0.75f * u) * perMetre;
        const glm::vec4 c = at(rgba, centre, row);
        const glm::vec4 want =
            glm::mix(glm::vec4(1, 0.8f, 0.2f, 1), glm::vec4(0.1f, 0.3f, 1, 1), u);
        std::cout << "u " << u << ": " << columns << " columns, expected " << expected
                  << "; centre " << c.r << " " << c.g << " " << c.b << "\n";
        EXPECT_NEAR(float(columns), expected, 1.5f) << "size at u = " << u;
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(c[ch], want[ch], 0.03f) << "colour at u = " << u << ", channel " << ch;
    }
}

TEST(VolumeLook, ReadsItsKeysOnEveryLitVolumeKind) {
    for (const char* type :
         {"motion_blur", "swept_volume", "silhouette_shell", "afterimage_smear"}) {
        SCOPED_TRACE(type);
        Result<scene::Scene> s = pointScene(R"({"type": ")" + std::string(type) + R"(",
            "colour_over_life": [{"at": 0, "colour": [1, 0, 0]}, {"at": 1, "colour": [0, 0, 1]}],
            "intensity": 2, "blend": "additive", "rim": 3, "rim_colour": [0.2, 0.6, 1]})");
        ASSERT_TRUE(s) << s.error().message;
        const scene::EffectSpec& e = s.value().effects.at(0);
        const scene::VolumeLook* look = nullptr;
        if (const auto* k = e.as<scene::MotionBlurSpec>()) look = &k->look;
        if (const auto* k = e.as<scene::SweptVolumeSpec>()) look = &k->look;
        if (const auto* k = e.as<scene::SilhouetteShellSpec>()) look = &k->look;
        if (const auto* k = e.as<scene::AfterimageSpec>()) look = &k->look;
        ASSERT_NE(look, nullptr);
        EXPECT_EQ(look->colourOverLife.size(), 2u);
        EXPECT_FLOAT_EQ(look->intensity, 2.0f);
        EXPECT_TRUE(look->additive);
        EXPECT_FLOAT_EQ(look->rim, 3.0f);
        EXPECT_EQ(look->rimColour, glm::vec3(0.2f, 0.6f, 1.0f));
    }
    Result<scene::Scene> lines =
        pointScene(R"({"type": "afterimage_smear", "variant": "speed_lines", "rim": 1})");
    ASSERT_FALSE(lines);
    EXPECT_NE(lines.error().message.find("effects[0].rim: only for the \"smear\" and \"multi\""),
              std::string::npos)
        << lines.error().message;
}

// The motion volume a sliding triangle 0.1 m across sweeps, its colour over life from pure red at
// its head to pure blue at its tail: whatever the lighting's tint, the red share r / (r + b) of
// the light it adds falls from 1 at the head to 0 at the tail, monotonically.
TEST_F(RibbonDrawTest, MotionVolumesTakeTheirColourOverLife) {
    const std::string blur = R"({"type": "motion_blur", "lifetime": 10, "alpha_start": 1,
        "alpha_end": 1, "blend": "additive",
        "colour_over_life": [{"at": 0, "colour": [1, 0, 0]}, {"at": 1, "colour": [0, 0, 1]}])";
    const std::vector<float> lit = draw(pointScene(blur + "}"), {0, 0, 1}, 0.1f);
    const std::vector<float> dark =
        draw(pointScene(blur + R"(, "intensity": 0})"), {0, 0, 1}, 0.1f);
    const int row = pixel(glm::vec3(0, 0.65f, 0)).y; // halfway up the swept wall
    const float head = column(kHead), tail = column(kTail);
    float previous = 2.0f;
    for (float u : {0.05f, 0.25f, 0.5f, 0.75f, 0.95f}) {
        const int x = int(std::lround(head - u * (head - tail)));
        const glm::vec4 added = at(lit, x, row) - at(dark, x, row);
        const float share = added.r / std::max(added.r + added.b, 1e-6f);
        std::cout << "u " << u << ": added " << added.r << " " << added.g << " " << added.b
                  << ", red share " << share << "\n";
        EXPECT_GT(added.r + added.b, 0.01f) << "the volume is there at u = " << u;
        EXPECT_LT(share, previous + 1e-3f) << "at u = " << u;
        EXPECT_NEAR(share, 1.0f - u, 0.05f) << "at u = " << u;
        previous = share;
    }
}

// The Fresnel rim on the same volume's wall (the plane z = 0, seen from behind at a point near the
// tail, where no other wall is along the ray): the light the rim adds there, over Schlick's F for
// the view, is the same seen at 70 degrees from the wall's normal (F about 0.16) and at a grazing
// 85 degrees (F about 0.65).
TEST_F(RibbonDrawTest, TheRimFollowsSchlicksFresnel) {
    const std::string blur = R"({"type": "motion_blur", "lifetime": 10, "alpha_start": 1,
        "alpha_end": 1, "blend": "additive", "rim_colour": [1, 1, 1], "rim": )";
    const glm::vec3 point(-0.15f, 0.65f, 0.0f); // on the wall, 0.8 of the way to the tail
    float perF[2];
    int k = 0;
    for (const float degrees : {70.0f, 85.0f}) {
        const float angle = glm::radians(degrees);
        const glm::vec3 eye = point + 2.0f * glm::vec3(std::sin(angle), 0.0f, -std::cos(angle));
        const std::string at3 =
            std::to_string(eye.x) + ", " + std::to_string(eye.y) + ", " + std::to_string(eye.z);
        const std::vector<float> none = draw(pointScene(blur + "0}", at3), {0, 0, 1}, 0.1f);
        const std::vector<float> rim = draw(pointScene(blur + "4}", at3), {0, 0, 1}, 0.1f);
        const glm::ivec2 p = pixel(point);
        const glm::vec4 added = at(rim, p.x, p.y) - at(none, p.x, p.y);
        const float fresnel = 0.04f + 0.96f * std::pow(1.0f - std::cos(angle), 5.0f);
        perF[k] = added.r / fresnel;
        std::cout << "view at " << degrees << " degrees: rim adds " << added.r << ", F " << fresnel
                  << ", over F " << perF[k] << "\n";
        EXPECT_NEAR(added.r, added.b, 1e-3f) << "white";
        ++k;
    }
    EXPECT_GT(perF[0], 0.2f) << "the rim is there";
    EXPECT_NEAR(perF[1] / perF[0], 1.0f, 0.1f);
}

} // namespace
} // namespace mfx::test
