// The smoke's own motion as a flipbook's motion vectors (`motionfx bake --motion velocity`,
// render/flipbook.h): the simulation's velocity carried to the screen. Each pixel's ray is marched
// through the grid's pigment as the smoke pass marches it (one sample a cell, density = pigment
// alpha times the look's density scale), and each sample's screen motion over `seconds`,
//     m = project(p + u(p) seconds) - project(p),   u the cell-centred velocity,
// is weighted by what the sample adds to the pixel, T a (T the transmittance before it, a its own
// opacity): the motion of what the pixel shows. Where the ray meets no smoke, 0.
#pragma once

#include "fluid/solver_options.h"
#include "render/flipbook.h"
#include "render/scene_camera.h"

#include <glm/glm.hpp>
#include <span>

namespace mfx::render {

// One grid's fields as read back (fluid::SmokeGrid::state) and where it is.
struct SmokeFields {
    const fluid::FieldState* state = nullptr;
    glm::vec3 origin{0.0f}; // world position of its low corner
};

// The motion in pixels of a `width` x `height` picture from `camera` (the bake's) over `seconds`.
MotionField projectedSmokeMotion(std::span<const SmokeFields> grids, const SceneCamera& camera,
                                 uint32_t width, uint32_t height, float seconds,
                                 float densityScale);

} // namespace mfx::render
