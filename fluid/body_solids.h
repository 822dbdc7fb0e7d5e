// The body's capsules (core/anim/body_capsules.h) as a smoke grid's solids for one step
// (shared::FluidSolid, docs/fluid.md "Solids"): posed where the step ends, in the grid's own
// coordinates, each end's velocity its motion over the step.
#pragma once

#include "core/anim/body_capsules.h"
#include "shaders/shared/fluid.h"

#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace mfx::fluid {

// `capsules` posed at `now` (the step's end) for a grid whose low corner lies at `origin` in the
// world; each end's velocity is (its position at `now` - at `before`) / dt. A radius below
// `thickness` / 2 is raised to it (thin parts such as a blade still block the air). dt > 0.
std::vector<shared::FluidSolid> bodySolids(std::span<const anim::BodyCapsule> capsules,
                                           const anim::Pose& before, const anim::Pose& now,
                                           float dt, glm::vec3 origin, float thickness = 0.0f);

} // namespace mfx::fluid
