// The viewer's orbit camera (render/orbit_camera.h): it starts where the scene's camera is, a drag
// turns it by the drag's pixels, the wheel scales its distance, a pan drag moves the target by the
// world size of the dragged pixels, and the printed camera block reads back as the same camera.
#include "render/orbit_camera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mfx::test {
namespace {

scene::CameraSpec sceneCamera() {
    scene::CameraSpec c;
    c.position = glm::vec3(1.85f, 1.3f, 2.45f);
    c.target = glm::vec3(0.0f, 0.92f, 0.0f);
    c.fovDegrees = 40.0f;
    return c;
}

void expectNear(glm::vec3 a, glm::vec3 b, float tolerance, const char* what) {
    EXPECT_LT(glm::length(a - b), tolerance)
        << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") against (" << b.x << ", " << b.y
        << ", " << b.z << ")";
}

TEST(OrbitCamera, StartsWhereTheScenesCameraIs) {
    const scene::CameraSpec c = sceneCamera();
    const render::OrbitCamera orbit = render::OrbitCamera::from(c);
    expectNear(orbit.position(), c.position, 1e-5f, "position");
    expectNear(orbit.apply(c).target, c.target, 1e-6f, "target");
    EXPECT_NEAR(orbit.distance(), glm::length(c.position - c.target), 1e-5f);
}

TEST(OrbitCamera, ADragTurnsItByItsPixelsAboutTheTarget) {
    render::OrbitCamera orbit = render::OrbitCamera::from(sceneCamera());
    const float yaw = orbit.yaw(), pitch = orbit.pitch(), distance = orbit.distance();
    orbit.orbit(100.0f, -40.0f);
    EXPECT_NEAR(orbit.yaw(), yaw - 100.0f * render::OrbitCamera::kRadiansPerPixel, 1e-6f);
    EXPECT_NEAR(orbit.pitch(), pitch - 40.0f * render::OrbitCamera::kRadiansPerPixel, 1e-6f);
    EXPECT_NEAR(glm::length(orbit.position() - orbit.target()), distance, 1e-5f)
        << "it stays as far from the target";
    // Back by the drag, plus a full turn: where it started.
    orbit.orbit(2.0f * 3.14159265f / render::OrbitCamera::kRadiansPerPixel - 100.0f, 40.0f);
    expectNear(orbit.position(), render::OrbitCamera::from(sceneCamera()).position(), 2e-3f,
               "after a full turn");
    // Pitch stops short of the pole, where the view's up would flip.
    orbit.orbit(0.0f, 1e5f);
    EXPECT_NEAR(orbit.pitch(), render::OrbitCamera::kMaxPitch, 1e-6f);
}

TEST(OrbitCamera, TheWheelScalesTheDistance) {
    render::OrbitCamera orbit = render::OrbitCamera::from(sceneCamera());
    const float distance = orbit.distance();
    orbit.zoom(3.0f);
    EXPECT_NEAR(orbit.distance(), distance * std::pow(0.9f, 3.0f), 1e-5f);
    orbit.zoom(-3.0f);
    EXPECT_NEAR(orbit.distance(), distance, 1e-5f);
    expectNear(orbit.target(), sceneCamera().target, 1e-6f, "the target stays");
}

// Dragging a view 500 pixels tall by 250 pixels moves the target by half the view's height at the
// target's distance, right to left (the scene follows the cursor), keeping the view's direction.
TEST(OrbitCamera, APanMovesTheTargetByTheDraggedPixelsWorldSize) {
    render::OrbitCamera orbit = render::OrbitCamera::from(sceneCamera());
    const glm::vec3 before = orbit.target();
    const glm::vec3 direction = glm::normalize(orbit.target() - orbit.position());
    const float viewHeight = 2.0f * orbit.distance() * std::tan(glm::radians(20.0f));
    orbit.pan(250.0f, 0.0f, 40.0f, 500.0f);
    const glm::vec3 moved = orbit.target() - before;
    EXPECT_NEAR(glm::length(moved), 0.5f * viewHeight, 1e-4f);
    EXPECT_NEAR(glm::dot(moved, direction), 0.0f, 1e-5f) << "in the view plane";
    EXPECT_NEAR(moved.y, 0.0f, 1e-5f) << "a sideways drag moves it sideways";
    const glm::vec3 right = glm::normalize(glm::cross(direction, glm::vec3(0, 1, 0)));
    EXPECT_LT(glm::dot(moved, right), 0.0f) << "dragging right moves the view's centre left";
    expectNear(glm::normalize(orbit.target() - orbit.position()), direction, 1e-5f, "direction");
    orbit.pan(0.0f, 500.0f, 40.0f, 500.0f);
    EXPECT_NEAR(glm::length(orbit.target() - before - moved), viewHeight, 1e-4f);
}

TEST(OrbitCamera, ItsCameraBlockReadsBackAsTheSameCamera) {
    render::OrbitCamera orbit = render::OrbitCamera::from(sceneCamera());
    orbit.orbit(37.0f, 12.0f);
    orbit.zoom(2.0f);
    orbit.pan(-20.0f, 9.0f, 40.0f, 540.0f);
    const scene::CameraSpec moved = orbit.apply(sceneCamera());
    const std::string block = render::cameraBlock(moved);
    Result<scene::Scene> s = scene::parseScene("{" + block + R"(, "effects": []})", "pasted.json");
    ASSERT_TRUE(s) << s.error().message << "\n" << block;
    expectNear(s.value().camera.position, moved.position, 1e-3f, "position");
    expectNear(s.value().camera.target, moved.target, 1e-3f, "target");
    EXPECT_FLOAT_EQ(s.value().camera.fovDegrees, 40.0f);
}

TEST(OrbitCamera, FramingFitsTheSphereInTheFieldOfViewFromTheSameDirection) {
    render::OrbitCamera orbit = render::OrbitCamera::from(sceneCamera());
    const glm::vec3 before = glm::normalize(orbit.position() - orbit.target());
    const glm::vec3 centre(0.3f, 1.0f, -0.2f);
    orbit.frame(centre, 0.9f, 40.0f);
    expectNear(orbit.target(), centre, 1e-6f, "target");
    expectNear(glm::normalize(orbit.position() - orbit.target()), before, 1e-5f, "direction");
    // The sphere's silhouette subtends half the field of view, less the 5% to spare.
    const float halfAngle = std::asin(0.9f / orbit.distance());
    EXPECT_NEAR(std::sin(halfAngle) * 1.05f, std::sin(glm::radians(20.0f)), 1e-5f);
}

} // namespace
} // namespace mfx::test
