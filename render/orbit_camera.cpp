#include "render/orbit_camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mfx::render {

OrbitCamera OrbitCamera::from(const scene::CameraSpec& camera) {
    OrbitCamera o;
    o.target_ = camera.target;
    const glm::vec3 offset = camera.position - camera.target;
    o.distance_ = std::max(glm::length(offset), 1e-6f);
    o.yaw_ = std::atan2(offset.x, offset.z);
    o.pitch_ = std::clamp(std::asin(std::clamp(offset.y / o.distance_, -1.0f, 1.0f)), -kMaxPitch,
                          kMaxPitch);
    return o;
}

glm::vec3 OrbitCamera::position() const {
    const float c = std::cos(pitch_);
    return target_ +
           distance_ * glm::vec3(c * std::sin(yaw_), std::sin(pitch_), c * std::cos(yaw_));
}

scene::CameraSpec OrbitCamera::apply(scene::CameraSpec camera) const {
    camera.position = position();
    camera.target = target_;
    camera.automatic = false;
    return camera;
}

void OrbitCamera::orbit(float dx, float dy) {
    yaw_ -= dx * kRadiansPerPixel;
    pitch_ = std::clamp(pitch_ + dy * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::zoom(float steps) {
    distance_ = std::clamp(distance_ * std::pow(kZoomPerStep, steps), 1e-3f, 1e4f);
}

void OrbitCamera::pan(float dx, float dy, float fovDegrees, float viewportHeight) {
    const glm::vec3 forward = glm::normalize(target_ - position());
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 up = glm::cross(right, forward);
    const float perPixel = 2.0f * distance_ * std::tan(0.5f * glm::radians(fovDegrees)) /
                           std::max(viewportHeight, 1.0f);
    target_ += (-dx * right + dy * up) * perPixel;
}

void OrbitCamera::frame(glm::vec3 centre, float radius, float fovDegrees) {
    target_ = centre;
    const float half = 0.5f * glm::radians(std::clamp(fovDegrees, 1.0f, 179.0f));
    distance_ = std::clamp(1.05f * std::max(radius, 1e-3f) / std::sin(half), 1e-3f, 1e4f);
}

std::string cameraBlock(const scene::CameraSpec& camera) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "\"camera\": {\"position\": [%.5g, %.5g, %.5g], \"target\": [%.5g, %.5g, %.5g], "
                  "\"fov_degrees\": %.5g}",
                  double(camera.position.x), double(camera.position.y), double(camera.position.z),
                  double(camera.target.x), double(camera.target.y), double(camera.target.z),
                  double(camera.fovDegrees));
    return text;
}

} // namespace mfx::render
