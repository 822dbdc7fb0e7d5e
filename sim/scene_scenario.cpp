#include "sim/scene_scenario.h"

#include "sim/scene_simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <span>

namespace mfx::sim {

namespace {

// Whether the solver takes one record (fluid::validateEmitters' checks; the splat shader itself
// skips records with a non-finite field).
bool acceptable(const shared::FluidEmitter& e) {
    return fluid::validateEmitters(std::span<const shared::FluidEmitter>(&e, 1)).ok();
}

} // namespace

Result<SceneImpulses> recordSceneImpulses(const gpu::Context& ctx, const scene::Scene& scene,
                                          const anim::Character& character, uint32_t maxSteps) {
    // Only the smoke effects: the speed-lines', blur's and particles' trajectories are separate
    // queues that no emitter reads.
    scene::Scene smokeOnly = scene;
    std::erase_if(smokeOnly.effects,
                  [](const scene::EffectSpec& e) { return !e.is<scene::SmokeSpec>(); });
    if (smokeOnly.effects.empty())
        return Error{scene.file + ": no smoke effect, so no impulses to record"};
    if (maxSteps == 0) return Error{"recording a scene's impulses needs at least one step"};
    auto created = SceneSimulation::create(ctx, smokeOnly, character);
    if (!created) return created.error();
    SceneSimulation& sim = *created.value();
    sim.setCaptureEmitters(true);

    const fluid::SmokeGrid& grid = sim.smokeGrids().front().grid;
    SceneImpulses out;
    out.scene = scene.file;
    out.grid = grid.name();
    out.options = grid.options();
    out.stepsPerSecond = smokeOnly.output.fps * float(grid.settings().stepsPerFrame);
    bool started = false;
    for (uint32_t frame = 0; frame < sim.frameCount() && out.steps.size() < maxSteps; ++frame) {
        sim.runFrame(frame);
        // A following grid has moved by whole cells since it was placed: records in its frame
        // plus that move are in the frame of the placed grid, which the replay keeps still.
        const glm::vec3 moved = grid.origin() - grid.placedOrigin();
        for (CapturedStep& step : sim.capturedEmitters(0)) {
            if (!started && step.emitters.empty()) continue;
            if (!started) out.firstStep = step.step;
            started = true;
            // A grid that slept skipped steps: they had no records.
            while (out.firstStep + out.steps.size() < step.step && out.steps.size() < maxSteps)
                out.steps.emplace_back();
            if (out.steps.size() == maxSteps) break;
            std::vector<shared::FluidEmitter> kept;
            kept.reserve(step.emitters.size());
            for (shared::FluidEmitter& e : step.emitters) {
                e.positionRadius += glm::vec4(moved, 0.0f);
                if (acceptable(e))
                    kept.push_back(e);
                else
                    ++out.dropped;
            }
            out.steps.push_back(std::move(kept));
        }
    }
    while (!out.steps.empty() && out.steps.back().empty())
        out.steps.pop_back();
    if (out.steps.empty())
        return Error{scene.file + ": " + out.grid + " received no usable emitters in " +
                     std::to_string(sim.frameCount()) + " frames (" + std::to_string(out.dropped) +
                     " refused)"};
    return out;
}

Result<fluid::Scenario> makeSceneScenario(const SceneImpulses& impulses, glm::uvec3 cells,
                                          const std::string& name) {
    if (cells.x == 0 || cells.y == 0 || cells.z == 0)
        return Error{"scenario \"" + name + "\": every grid dimension must be at least 1"};
    fluid::Scenario s;
    s.name = name;
    s.options = impulses.options;
    s.options.grid = {cells.x, cells.y, cells.z,
                      1.0f / float(std::max({cells.x, cells.y, cells.z}))};
    const fluid::GridShape& from = impulses.options.grid;
    const glm::vec3 fromExtent = glm::vec3(from.cellsX, from.cellsY, from.cellsZ) * from.cellSize;
    const glm::vec3 toExtent = glm::vec3(cells) * s.options.grid.cellSize;
    const glm::vec3 scale = toExtent / fromExtent;
    const float radiusScale = std::cbrt(scale.x * scale.y * scale.z);
    s.options.buoyancy *= scale.y;
    s.initial = fluid::FieldState::zero(s.options.grid);

    auto steps = std::make_shared<std::vector<std::vector<shared::FluidEmitter>>>();
    steps->reserve(impulses.steps.size());
    for (const std::vector<shared::FluidEmitter>& step : impulses.steps) {
        std::vector<shared::FluidEmitter> mapped = step;
        for (shared::FluidEmitter& e : mapped) {
            e.positionRadius =
                glm::vec4(glm::vec3(e.positionRadius) * scale, e.positionRadius.w * radiusScale);
            e.velocityStrength =
                glm::vec4(glm::vec3(e.velocityStrength) * scale, e.velocityStrength.w);
        }
        steps->push_back(std::move(mapped));
    }
    size_t most = 0;
    for (const std::vector<shared::FluidEmitter>& step : *steps)
        most = std::max(most, step.size());
    char rate[32];
    std::snprintf(rate, sizeof rate, "%g", double(impulses.stepsPerSecond));
    s.description = "impulses recorded from " + impulses.scene + ", grid " + impulses.grid + ": " +
                    std::to_string(steps->size()) + " steps at " + rate +
                    " per second from scene step " + std::to_string(impulses.firstStep) +
                    ", up to " + std::to_string(most) +
                    " emitters per step, mapped onto the domain";
    s.emitters = [steps](uint32_t step) {
        return step < steps->size() ? (*steps)[step] : std::vector<shared::FluidEmitter>{};
    };
    return s;
}

Result<fluid::Scenario> recordSceneScenario(const gpu::Context& ctx, const scene::Scene& scene,
                                            const anim::Character& character, glm::uvec3 cells,
                                            uint32_t maxSteps) {
    Result<SceneImpulses> impulses = recordSceneImpulses(ctx, scene, character, maxSteps);
    if (!impulses) return impulses.error();
    return makeSceneScenario(impulses.value(), cells);
}

} // namespace mfx::sim
