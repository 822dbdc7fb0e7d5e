// The camera and key light of a scene as the render passes use them.
#pragma once

#include "core/scene/scene.h"
#include "shaders/shared/scene_draw.h"

#include <glm/glm.hpp>

namespace mfx::render {

struct SceneCamera {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f}; // Vulkan depth 0..1, right-handed; the target flips y
    glm::mat4 viewProjection{1.0f};
    glm::vec3 eye{0.0f};
    float nearPlane = 0.05f;
    float farPlane = 50.0f;
};

SceneCamera makeCamera(const scene::CameraSpec& camera, float aspect);

// The key light's view of the character's surroundings: an orthographic box of half-size
// `radius` around `centre`, looking along the light's direction. Vulkan depth 0..1.
glm::mat4 lightViewProjection(const scene::LightSpec& light, glm::vec3 centre, float radius);

// The frame uniform of the scene pass: the camera and the scene's first light (the key light);
// without a shadow map (shadowSize 0) nothing is in shadow.
shared::SceneFrame sceneFrame(const scene::Scene& scene, const SceneCamera& camera,
                              const glm::mat4& lightViewProjection = glm::mat4(1.0f),
                              uint32_t shadowSize = 0);

} // namespace mfx::render
