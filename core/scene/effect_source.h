// The vertices an effect binds: the one selection every consumer of an effect uses (the
// simulation's trajectory queues, sim/scene_simulation.cpp, and the mesh-effect passes,
// render/kinds/afterimage_pass.h and its siblings), so they cannot disagree.
#pragma once

#include "core/anim/character.h"
#include "core/result.h"
#include "core/scene/scene.h"
#include "core/trajectory/surface_source.h"
#include "core/trajectory/trajectory_source.h"

namespace mfx::scene {

// Effect `e`'s vertices on `character`: those of its meshes (all without "meshes") whose weights
// to its bones sum to at least min_bone_weight (all without "bones"); for smoke with surface
// emission, points sampled on those vertices' triangles every surface_step of UV space
// (`surface`, when given, gets what was sampled). Fails as trajectory::selectSource and
// selectSurfaceSource do, naming what is wrong.
Result<trajectory::Source> effectSource(const anim::Character& character, const EffectSpec& e,
                                        trajectory::SurfaceReport* surface = nullptr);

} // namespace mfx::scene
