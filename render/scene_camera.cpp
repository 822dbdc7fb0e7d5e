#include "render/scene_camera.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

namespace mfx::render {

SceneCamera makeCamera(const scene::CameraSpec& spec, float aspect) {
    SceneCamera c;
    c.eye = spec.position;
    c.nearPlane = spec.nearPlane;
    c.farPlane = spec.farPlane;
    glm::vec3 up(0.0f, 1.0f, 0.0f);
    const glm::vec3 forward = glm::normalize(spec.target - spec.position);
    if (std::abs(glm::dot(forward, up)) > 0.999f)
        up = glm::vec3(0.0f, 0.0f, -1.0f); // straight down
    c.view = glm::lookAt(spec.position, spec.target, up);
    c.projection =
        glm::perspectiveRH_ZO(glm::radians(spec.fovDegrees), aspect, spec.nearPlane, spec.farPlane);
    c.viewProjection = c.projection * c.view;
    return c;
}

Result<SceneCamera> cameraFromMatrices(const glm::mat4& view, const glm::mat4& projection,
                                       bool clipYDown) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(view[c][r]) || !std::isfinite(projection[c][r]))
                return Error{std::string("camera.") +
                             (std::isfinite(view[c][r]) ? "projection" : "view") + "[" +
                             std::to_string(c * 4 + r) + "] is not a finite number"};
    // A perspective projection to depth 0..1 takes view-space z to clip w = -z and clip z =
    // A z + B with A = far / (near - far), B = near far / (near - far): near = B / A and
    // far = B / (A + 1).
    const float w = projection[2][3], a = projection[2][2], b = projection[3][2];
    if (std::abs(w + 1.0f) > 1e-4f || projection[3][3] != 0.0f)
        return Error{"camera.projection is not a right-handed perspective projection (clip w "
                     "must be -z in view space: projection[11] = -1 and projection[15] = 0)"};
    const float nearPlane = a != 0.0f ? b / a : 0.0f;
    const float farPlane = a + 1.0f != 0.0f ? b / (a + 1.0f) : 0.0f;
    if (!(nearPlane > 0.0f) || !(farPlane > nearPlane) || !std::isfinite(farPlane))
        return Error{"camera.projection does not map depth 0 to a near plane and 1 to a farther, "
                     "finite far plane (reversed or infinite depth is not supported); its planes "
                     "read as near " +
                     std::to_string(nearPlane) + ", far " + std::to_string(farPlane)};
    const glm::mat4 inverseView = glm::inverse(view);
    if (!std::isfinite(inverseView[3][0]) || std::abs(glm::determinant(view)) < 1e-12f)
        return Error{"camera.view cannot be inverted"};
    SceneCamera c;
    c.view = view;
    c.projection = projection;
    if (clipYDown) // row 1 negated: clip-space y up again, as motionfx's flipped viewport wants
        for (int col = 0; col < 4; ++col)
            c.projection[col][1] = -c.projection[col][1];
    c.viewProjection = c.projection * c.view;
    c.eye = glm::vec3(inverseView[3]);
    c.nearPlane = nearPlane;
    c.farPlane = farPlane;
    return c;
}

glm::mat4 lightViewProjection(const scene::LightSpec& light, glm::vec3 centre, float radius) {
    const glm::vec3 d = glm::normalize(light.direction);
    const glm::vec3 up = std::abs(d.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    const float distance = 4.0f * radius;
    const glm::mat4 view = glm::lookAt(centre - d * distance, centre, up);
    const glm::mat4 projection =
        glm::orthoRH_ZO(-radius, radius, -radius, radius, 0.01f, 2.0f * distance);
    return projection * view;
}

shared::SceneFrame sceneFrame(const scene::Scene& scene, const SceneCamera& camera,
                              const glm::mat4& lightViewProjection, uint32_t shadowSize) {
    shared::SceneFrame f{};
    f.viewProjection = camera.viewProjection;
    f.cameraPosition = glm::vec4(camera.eye, 1.0f);
    const scene::LightSpec key = scene.lights.empty() ? scene::LightSpec{} : scene.lights.front();
    f.lightDirection = glm::vec4(-glm::normalize(key.direction), 0.0f);
    f.lightColor = glm::vec4(key.colour * key.intensity, 0.28f);
    f.sky = glm::vec4(0.75f, 0.82f, 1.0f, 0.3f);
    f.ground = glm::vec4(0.35f, 0.3f, 0.28f, 40.0f);
    f.lightViewProjection = lightViewProjection;
    const bool shadow = shadowSize > 0 && key.shadow;
    f.shadow = glm::vec4(shadow ? 1.0f : 0.0f, 0.0015f,
                         shadowSize > 0 ? 1.0f / float(shadowSize) : 0.0f, 0.0f);
    f.depthRange = glm::vec4(camera.nearPlane, camera.farPlane, 0.0f, 0.0f);
    return f;
}

} // namespace mfx::render
