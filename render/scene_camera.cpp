#include "render/scene_camera.h"

#include <glm/gtc/matrix_transform.hpp>

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
