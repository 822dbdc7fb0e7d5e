// Uniform surface emission: points spread evenly over the fighter's surface, degenerate UVs
// handled, overlapping UVs detected.
#include "core/anim/fighter.h"
#include "core/trajectory/surface_source.h"

#include <cmath>
#include <gtest/gtest.h>

namespace mfx::test {
namespace {

TEST(SurfaceSource, FighterGetsAnEvenDensity) {
    const anim::Character fighter = anim::makeFighter();
    const float step = 0.004f;
    trajectory::SurfaceReport report;
    const auto source = trajectory::selectSurfaceSource(fighter, {}, step, &report);
    ASSERT_TRUE(source.ok()) << source.error().message;
    EXPECT_EQ(report.withoutUv, 0u);
    EXPECT_TRUE(report.overlappingMeshes.empty());
    double area = 0.0;
    for (double a : report.triangleAreas)
        area += a;
    const double expected = 1.0 / (double(step) * double(step)); // points per square metre
    const double overall = double(report.samples) / area;
    // Per triangle: only where the lattice's count can be within 10% at all (at least 100
    // expected points; a triangle's count is off by about its perimeter over the step).
    size_t checked = 0, within = 0;
    double worst = 0.0;
    for (size_t t = 0; t < report.triangleAreas.size(); ++t) {
        const double n = report.triangleAreas[t] * expected;
        if (n < 100.0) continue;
        ++checked;
        const double error = std::abs(double(report.triangleSamples[t]) - n) / n;
        worst = std::max(worst, error);
        within += error <= 0.10 ? 1 : 0;
    }
    std::printf("%zu triangles, %.3f m² of surface: %zu points, %.0f per m² (expected %.0f); %zu "
                "triangles with >= 100 expected points, worst %.1f%% off\n",
                report.triangles, area, report.samples, overall, expected, checked, 100.0 * worst);
    EXPECT_NEAR(overall, expected, 0.02 * expected);
    ASSERT_GT(checked, 100u);
    EXPECT_EQ(within, checked);
}

anim::Character twoTriangles(bool degenerateUv, bool overlap) {
    anim::Character c;
    c.name = "patch";
    anim::Node root;
    root.name = "root";
    c.nodes.push_back(root);
    anim::Mesh mesh;
    mesh.name = "patch";
    anim::Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    p.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    p.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    if (degenerateUv) p.uvs[3] = {0.5f, 0.5f}; // on the diagonal from (1,0) to (0,1)
    if (overlap) p.uvs[3] = {0.1f, 0.1f};      // folds the second triangle over the first
    p.indices = {0, 1, 2, 1, 3, 2};
    p.node = 0;
    mesh.primitives.push_back(p);
    c.meshes.push_back(mesh);
    anim::Clip clip;
    clip.name = "still";
    c.clips.push_back(clip);
    return c;
}

TEST(SurfaceSource, TriangleDegenerateInUvIsSkippedAndCounted) {
    const anim::Character c = twoTriangles(true, false);
    trajectory::SurfaceReport report;
    const auto source = trajectory::selectSurfaceSource(c, {}, 0.05f, &report);
    ASSERT_TRUE(source.ok()) << source.error().message;
    EXPECT_EQ(report.degenerateInUv, 1u);
    EXPECT_EQ(report.triangleSamples[1], 0u);
    EXPECT_NEAR(double(report.triangleSamples[0]), 0.5 / (0.05 * 0.05), 0.1 * 200.0);
    for (const shared::SkinVertexIn& v : source.value().vertices) {
        ASSERT_TRUE(std::isfinite(v.position.x) && std::isfinite(v.position.y));
        EXPECT_LE(v.position.x + v.position.y, 1.0f + 1e-5f); // on the first triangle
        EXPECT_FLOAT_EQ(v.position.z, 0.0f);
        EXPECT_FLOAT_EQ(v.weights.x + v.weights.y + v.weights.z + v.weights.w, 1.0f);
    }
}

TEST(SurfaceSource, OverlappingUvsAreReported) {
    trajectory::SurfaceReport report;
    ASSERT_TRUE(
        trajectory::selectSurfaceSource(twoTriangles(false, true), {}, 0.05f, &report).ok());
    ASSERT_EQ(report.overlappingMeshes.size(), 1u);
    EXPECT_EQ(report.overlappingMeshes[0], "patch");
    ASSERT_TRUE(
        trajectory::selectSurfaceSource(twoTriangles(false, false), {}, 0.05f, &report).ok());
    EXPECT_TRUE(report.overlappingMeshes.empty());
}

TEST(SurfaceSource, BadStepsAreRefused) {
    const anim::Character c = twoTriangles(false, false);
    EXPECT_FALSE(trajectory::selectSurfaceSource(c, {}, 0.0f).ok());
    EXPECT_FALSE(trajectory::selectSurfaceSource(c, {}, std::nanf("")).ok());
    const auto tooFine = trajectory::selectSurfaceSource(c, {}, 1e-5f, nullptr, 10000);
    ASSERT_FALSE(tooFine.ok());
    EXPECT_NE(tooFine.error().message.find("use a larger step"), std::string::npos);
}

} // namespace
} // namespace mfx::test
