// The viewer's camera under the mouse: an orbit about a target point, as DCC tools' turntable
// cameras move: left drag orbits (yaw about the world's up, pitch up to 89 degrees either way),
// the wheel zooms (each step 0.9 of the distance, or 1 / 0.9 back), and a middle or shift drag pans
// (the point under the cursor follows it: the target moves in the view plane by the world size of
// the dragged pixels at the target's distance). cameraBlock prints the camera as a scene file's
// "camera" block, ready to paste.
#pragma once

#include "core/scene/scene.h"

#include <glm/glm.hpp>
#include <string>

namespace mfx::render {

class OrbitCamera {
public:
    static constexpr float kRadiansPerPixel = 0.005f;
    static constexpr float kZoomPerStep = 0.9f;
    static constexpr float kMaxPitch = 1.5533430f; // 89 degrees

    // The orbit that puts the camera where `camera` has it (its position about its target).
    static OrbitCamera from(const scene::CameraSpec& camera);

    // `camera` moved to this orbit (its lens and planes kept).
    scene::CameraSpec apply(scene::CameraSpec camera) const;

    // A drag of (dx, dy) pixels (x right, y down): the camera goes round the target to the left
    // as the drag goes right, and up over it as the drag goes down.
    void orbit(float dx, float dy);
    // `steps` wheel steps: positive closer.
    void zoom(float steps);
    // A pan drag of (dx, dy) pixels in a view `viewportHeight` pixels tall with a vertical field
    // of view of `fovDegrees`.
    void pan(float dx, float dy, float fovDegrees, float viewportHeight);
    // Aims at `centre` from the distance at which a sphere of `radius` about it just fits the
    // vertical field of view `fovDegrees`, with 5% to spare; the direction is kept.
    void frame(glm::vec3 centre, float radius, float fovDegrees);

    glm::vec3 target() const { return target_; }
    glm::vec3 position() const;
    float distance() const { return distance_; }
    float yaw() const { return yaw_; }
    float pitch() const { return pitch_; }

private:
    glm::vec3 target_{0.0f};
    float distance_ = 1.0f;
    float yaw_ = 0.0f;   // about +y, 0 looking from +z
    float pitch_ = 0.0f; // above the target's horizontal plane
};

// `"camera": {"position": [...], "target": [...], "fov_degrees": ...}` of `camera`, to paste into
// a scene file (numbers to 5 significant digits).
std::string cameraBlock(const scene::CameraSpec& camera);

} // namespace mfx::render
