// The body's capsules (core/anim/body_capsules.h) as a smoke grid's solids for one step
// (shared::FluidSolid, docs/fluid.md "Solids"): posed where the step ends, in the grid's own
// coordinates, each end's velocity its motion over the step.
#pragma once

#include "core/anim/body_capsules.h"
#include "fluid/grid.h"
#include "shaders/shared/fluid.h"

#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace mfx::fluid {

// `capsules` posed at `now` (the step's end) and carried into the world by `placement` (the
// character's placement: a rotation, a uniform scale and a translation) for a grid whose low
// corner lies at `origin` in the world; each end's velocity is (its position at `now` - at
// `before`) / dt. A radius below `thickness` / 2 (world units) is raised to it (thin parts such as
// a blade still block the air). dt > 0.
std::vector<shared::FluidSolid> bodySolids(std::span<const anim::BodyCapsule> capsules,
                                           const anim::Pose& before, const anim::Pose& now,
                                           float dt, glm::vec3 origin, float thickness = 0.0f,
                                           const glm::mat4& placement = glm::mat4(1.0f));

// The cells of `grid` whose centre lies inside one of `solids` (grid coordinates), one flag per
// cell x-fastest: the solid cells markSolids makes of them (docs/fluid.md, "Solids"), found on the
// CPU; and their count.
std::vector<uint8_t> solidCellMask(const GridShape& grid,
                                   std::span<const shared::FluidSolid> solids);
uint64_t countSolidCells(const GridShape& grid, std::span<const shared::FluidSolid> solids);

} // namespace mfx::fluid
