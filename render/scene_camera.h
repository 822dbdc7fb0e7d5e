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

// The frame uniform of the scene pass: the camera and the scene's first light (the key light).
shared::SceneFrame sceneFrame(const scene::Scene& scene, const SceneCamera& camera);

} // namespace mfx::render
