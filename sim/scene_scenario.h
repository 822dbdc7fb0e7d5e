// A scene's smoke impulses as a solver scenario (fluid/scenarios.h), so that `motionfx bench
// accuracy` and the tests can run the GPU solver and the CPU reference on the impulses a real
// scene makes: for the built-in default scene, the roundhouse kick's foot (scenario `kick`).
//
// recordSceneImpulses runs the scene frame by frame on the GPU (SceneSimulation, with its emitter
// capture on) and reads back the emitter records (shared::FluidEmitter) every step of the scene's
// first smoke grid splatted, in that grid's frame. makeSceneScenario maps them onto a scenario grid
// of any size, so one recording serves a grid and the grid twice as fine.
#pragma once

#include "core/anim/character.h"
#include "core/result.h"
#include "core/scene/scene.h"
#include "fluid/scenarios.h"
#include "fluid/solver_options.h"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace mfx::gpu {
class Context;
}

namespace mfx::sim {

// What one recording holds.
struct SceneImpulses {
    std::string scene;            // where the scene came from (its file, or the built-in default)
    std::string grid;             // the recorded grid's name in the scene ("smoke0")
    fluid::SolverOptions options; // the scene grid's solver options: shape, dt per step, fade, ...
    uint64_t firstStep = 0;       // the scene step of steps[0] (steps are 1 / rate seconds)
    float stepsPerSecond = 60.0f; // the grid's step rate
    std::vector<std::vector<shared::FluidEmitter>> steps; // per step, in the scene grid's frame
    uint32_t dropped =
        0; // records left out because the solver refuses them (fluid::validateEmitters)
};

// Steps one recording keeps at most: 2 s of a 60-steps-per-second grid, more than the default
// scene's kick lasts (0.9 s, 53 steps).
inline constexpr uint32_t kSceneImpulsesMaxSteps = 120;

// Runs `scene` (with `character`, both loaded and checked) on the GPU and records the emitter
// records each step of its first smoke grid receives. Kept: the steps from the first one with any
// record (a step whose effects are not live has none), for as long as the scene runs, at most
// `maxSteps`; trailing steps without records are dropped. Records with a non-finite field (which
// the splat shader ignores), a radius <= 0, a negative strength or negative pigment (which the
// solver's setEmitters refuses) are left out and counted. Only the scene's smoke effects are run
// (the others do not change the records). A grid that follows the character is recorded in the
// frame of where it was first placed (records plus how far the grid has moved), so the replay,
// on a grid that stays put, sees the impulses where they were in the world. An error when the
// scene has no smoke effect, when its simulation cannot be made, or when no step has records.
Result<SceneImpulses> recordSceneImpulses(const gpu::Context& ctx, const scene::Scene& scene,
                                          const anim::Character& character,
                                          uint32_t maxSteps = kSceneImpulsesMaxSteps);

// The recording as a scenario named `name` on a grid of `cells` (cell size 1 / the largest
// dimension, the domain's longest side 1 world unit, as makeScenario's). The scene grid's domain
// is mapped onto the scenario's, axis by axis, so the motion fills the same fraction of the domain:
// positions and velocities are scaled by (scenario extent / scene extent) per axis, radii by the
// cube root of the three factors' product (the same factor when the two grids have the same
// shape). Emitter strengths (per second) and pigment are kept.
// Options kept from the scene grid: dt per step and sub-steps, boundaries (open, the floor a
// free-slip wall), fade and drag (per second), vorticity, viscosity, integrator, pressure solver
// and its effort (Jacobi sweeps), advection and storage; buoyancy (an acceleration) is scaled by
// the vertical factor. Taken from the scenario grid: the cells and the cell size. The initial
// state is empty (at rest, no pigment); emitters(step) past the recording are empty.
// An error when a dimension of `cells` is 0.
Result<fluid::Scenario> makeSceneScenario(const SceneImpulses& impulses, glm::uvec3 cells,
                                          const std::string& name = "kick");

// recordSceneImpulses then makeSceneScenario.
Result<fluid::Scenario> recordSceneScenario(const gpu::Context& ctx, const scene::Scene& scene,
                                            const anim::Character& character, glm::uvec3 cells,
                                            uint32_t maxSteps = kSceneImpulsesMaxSteps);

} // namespace mfx::sim
