// The camera and key light of a scene as the render passes use them.
#pragma once

#include "core/result.h"
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

// A camera from a host application's matrices (the runtime library's MfxCamera): `view` world to
// view, right-handed; `projection` a perspective one to Vulkan's clip space with depth 0 at the
// near plane and 1 at the far one, clip-space +y up or, with `clipYDown`, down (flipped for a
// viewport of positive height). The planes are read from the projection; a projection that is
// not such a perspective (orthographic, reversed or infinite depth, NaN) is refused, naming why.
Result<SceneCamera> cameraFromMatrices(const glm::mat4& view, const glm::mat4& projection,
                                       bool clipYDown);

// The key light's view of the character's surroundings: an orthographic box of half-size
// `radius` around `centre`, looking along the light's direction. Vulkan depth 0..1.
glm::mat4 lightViewProjection(const scene::LightSpec& light, glm::vec3 centre, float radius);

// The frame uniform of the scene pass: the camera and the scene's first light (the key light);
// without a shadow map (shadowSize 0) nothing is in shadow.
shared::SceneFrame sceneFrame(const scene::Scene& scene, const SceneCamera& camera,
                              const glm::mat4& lightViewProjection = glm::mat4(1.0f),
                              uint32_t shadowSize = 0);

} // namespace mfx::render
