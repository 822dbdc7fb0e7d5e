#include "sim/scene_simulation.h"

#include "core/scene/effect_source.h"
#include "core/scene/scene_fit.h"

#include "core/anim/sampling.h"
#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "core/trajectory/build_segment.h"
#include "core/trajectory/surface_source.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

namespace mfx::sim {

namespace {

constexpr uint32_t kMaxPasses = 512;

trajectory::Kind kindOf(scene::EffectType type) {
    switch (type) {
    case scene::EffectType::SpeedLines:
        return trajectory::Kind::Lines;
    case scene::EffectType::MotionBlur:
        return trajectory::Kind::Volumes;
    case scene::EffectType::MotionParticles:
    case scene::EffectType::Smoke:
    case scene::EffectType::AfterimageSmear: // no queue (render/afterimage_pass.h)
    case scene::EffectType::SweptVolume:     // no queue (render/swept_volume_pass.h)
    case scene::EffectType::SilhouetteShell: // no queue (render/silhouette_shell_pass.h)
        return trajectory::Kind::Particles;
    }
    return trajectory::Kind::Lines;
}

// Every stride-th vertex of `source` (triangles dropped: only volumes use them, and volumes keep
// every vertex).
trajectory::Source strided(const trajectory::Source& source, uint32_t stride) {
    if (stride <= 1) return source;
    trajectory::Source out;
    out.palette = source.palette;
    for (size_t v = 0; v < source.vertices.size(); v += stride) {
        out.vertices.push_back(source.vertices[v]);
        out.colours.push_back(source.colours[v]);
        if (v < source.uvs.size()) out.uvs.push_back(source.uvs[v]);
    }
    return out;
}

bool sameGrid(const scene::EffectSpec& a, const scene::EffectSpec& b) {
    return a.grid == b.grid && a.cellSize == b.cellSize && a.jacobi == b.jacobi &&
           a.fade == b.fade && a.drag == b.drag && a.buoyancy == b.buoyancy &&
           a.vorticity == b.vorticity && a.stepsPerSecond == b.stepsPerSecond &&
           a.follow == b.follow;
}

} // namespace

uint32_t SimulationFrameStats::dispatches() const {
    uint32_t n = 0;
    for (const PassRecord& p : passes)
        n += p.dispatches;
    return n;
}

uint32_t SimulationFrameStats::fluidDispatches() const {
    uint32_t n = 0;
    for (const PassRecord& p : passes)
        if (p.name.rfind("smoke", 0) == 0) n += p.dispatches;
    return n;
}

Result<std::unique_ptr<SceneSimulation>> SceneSimulation::create(const gpu::Context& ctx,
                                                                 const scene::Scene& scene,
                                                                 const anim::Character& character) {
    std::unique_ptr<SceneSimulation> sim(new SceneSimulation(ctx, scene, character));
    // Bone groups and patterns resolved, automatic bones, strides, camera and stage chosen (a
    // scene the caller fitted already is left as it is).
    if (Status fitted = scene::fitScene(sim->scene_, character); !fitted) return fitted.error();
    sim->frames_ = scene::frameCount(sim->scene_, character);
    for (size_t i = 0; i < sim->scene_.effects.size(); ++i) {
        const scene::EffectSpec& e = sim->scene_.effects[i];
        const std::string where =
            sim->scene_.file + ": effects[" + std::to_string(i) + "] (\"" + e.name + "\"): ";
        TrajectoryEffect effect;
        effect.spec = &e;
        const bool surface =
            e.type == scene::EffectType::Smoke && e.emission == scene::Emission::Surface;
        Result<trajectory::Source> selected = scene::effectSource(character, e, &effect.surface);
        if (!selected) return Error{where + selected.error().message};
        // The afterimage smear keeps its own per-vertex history in the renderer (it deforms the
        // mesh as drawn, render/afterimage_pass.h); it has no trajectory queue.
        // So do the swept volume (render/swept_volume_pass.h) and the silhouette shell
        // (render/silhouette_shell_pass.h).
        if (e.type == scene::EffectType::AfterimageSmear ||
            e.type == scene::EffectType::SweptVolume ||
            e.type == scene::EffectType::SilhouetteShell)
            continue;
        effect.source = e.type == scene::EffectType::MotionBlur || surface
                            ? std::move(selected).value()
                            : strided(selected.value(), e.stride);
        if (!e.useMeshColour)
            std::fill(effect.source.colours.begin(), effect.source.colours.end(), e.colour);
        trajectory::QueueOptions options;
        options.kind = kindOf(e.type);
        options.segment.subSamples = e.subSamples;
        options.segment.impulseScale = e.impulseScale;
        options.segment.alphaStart = e.alphaStart;
        options.segment.alphaEnd = e.alphaEnd;
        options.segment.alphaPower = e.alphaPower;
        options.lifetime = e.lifetime;
        options.maxLifetime = e.lifetime;
        auto queue = trajectory::Queue::create(ctx, effect.source, options);
        if (!queue) return Error{where + queue.error().message};
        effect.queue = std::move(queue).value();
        sim->trajectories_.push_back(std::move(effect));
    }

    // Smoke effects with the same grid settings share a grid.
    for (size_t i = 0; i < sim->trajectories_.size(); ++i) {
        const scene::EffectSpec& e = *sim->trajectories_[i].spec;
        if (e.type != scene::EffectType::Smoke) continue;
        auto shared = std::find_if(sim->grids_.begin(), sim->grids_.end(), [&](const SmokeGrid& g) {
            return sameGrid(*sim->trajectories_[g.effects.front()].spec, e);
        });
        if (shared != sim->grids_.end()) {
            shared->effects.push_back(i);
            shared->sleepThreshold = std::min(shared->sleepThreshold, e.sleepThreshold);
            continue;
        }
        SmokeGrid grid;
        grid.name = "smoke" + std::to_string(sim->grids_.size());
        grid.effects.push_back(i);
        grid.sleepThreshold = e.sleepThreshold;
        sim->grids_.push_back(std::move(grid));
    }
    for (SmokeGrid& grid : sim->grids_) {
        const scene::EffectSpec& e = *sim->trajectories_[grid.effects.front()].spec;
        fluid::SolverOptions options;
        options.grid = fluid::GridShape{e.grid[0], e.grid[1], e.grid[2], e.cellSize};
        grid.stepsPerFrame =
            std::max(1u, uint32_t(std::ceil(e.stepsPerSecond / sim->scene_.output.fps - 1e-4f)));
        options.dt = 1.0f / (sim->scene_.output.fps * float(grid.stepsPerFrame));
        options.fade = e.fade;
        options.drag = e.drag;
        options.buoyancy = e.buoyancy;
        options.vorticity = e.vorticity;
        options.jacobiIterations = e.jacobi;
        for (fluid::FaceBoundary& face : options.boundaries)
            face.kind = fluid::Boundary::Open;
        options.boundaries[fluid::FaceLowY].kind = fluid::Boundary::WallFreeSlip; // the stage floor
        auto solver = fluid::SmokeSolver::create(ctx, options);
        if (!solver)
            return Error{sim->scene_.file + ": " + grid.name + ": " + solver.error().message};
        grid.solver = std::move(solver).value();
        uint32_t capacity = 0;
        for (size_t i : grid.effects)
            capacity += sim->trajectories_[i].spec->maxEmitters;
        // Transfer source for setCaptureEmitters' copies.
        grid.emitters =
            gpu::createBuffer(ctx, capacity * sizeof(shared::FluidEmitter),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                              gpu::MemoryUsage::DeviceLocal, "smoke emitters");
        grid.activity =
            gpu::createBuffer(ctx, 2 * sizeof(uint32_t),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                              gpu::MemoryUsage::Readback, "smoke activity");
        if (Status placed = sim->placeGrid(grid); !placed) return placed.error();
        grid.follow = e.follow;
        grid.placedOrigin = grid.origin;
        grid.rootAtPlacement = sim->rootPosition(sim->poseAt(sim->frameTime(0)));
    }
    if (!sim->grids_.empty()) sim->coupling_ = std::make_unique<fluid::SegmentEmitters>(ctx);
    sim->timer_ = gpu::GpuTimer(ctx, kMaxPasses);
    return sim;
}

glm::mat4 SceneSimulation::placement() const {
    return scene::characterPlacement(scene_);
}

bool SceneSimulation::effectLive(const scene::EffectSpec& e, float time) const {
    return scene::effectLive(scene_, e, time);
}

// The grid is centred on the bounds its effects' vertices sweep over their windows (sampled at
// the frame rate), and stands on the floor (y = stage.floorHeight) when the stage has one and the
// bounds allow.
Status SceneSimulation::placeGrid(SmokeGrid& grid) {
    glm::vec3 low(std::numeric_limits<float>::max()), high(std::numeric_limits<float>::lowest());
    const anim::Clip& clip = scene::sceneClip(scene_, character_);
    for (size_t i : grid.effects) {
        const TrajectoryEffect& effect = trajectories_[i];
        for (uint32_t f = 0; f < frames_; ++f) {
            const float t = frameTime(f);
            if (!effectLive(*effect.spec, t)) continue;
            const anim::Pose pose = anim::samplePose(
                character_, &clip, scene::clipTimeAt(scene_, character_, t), anim::Wrap::Clamp);
            const auto transforms = trajectory::vertexTransforms(
                effect.source,
                trajectory::sourcePalette(character_, effect.source, pose, placement()));
            for (size_t v = 0; v < transforms.size(); ++v) {
                const glm::vec3 p =
                    anim::applyTransform(transforms[v],
                                         glm::vec3(effect.source.vertices[v].position),
                                         glm::vec3(0, 1, 0))
                        .position;
                low = glm::min(low, p);
                high = glm::max(high, p);
            }
        }
    }
    const fluid::GridShape& shape = grid.solver->options().grid;
    const glm::vec3 extent =
        glm::vec3(float(shape.cellsX), float(shape.cellsY), float(shape.cellsZ)) * shape.cellSize;
    if (low.x > high.x) { // no live frame at all: centre on the character's origin
        low = high = scene_.character.position + glm::vec3(0.0f, 0.5f * extent.y, 0.0f);
    }
    grid.origin = 0.5f * (low + high) - 0.5f * extent;
    const float floor = scene_.stage.floorHeight;
    if (scene_.stage.floor && grid.origin.y < floor && low.y >= floor) grid.origin.y = floor;
    return Ok{};
}

anim::Pose SceneSimulation::poseAt(float time) const {
    const anim::Clip& clip = scene::sceneClip(scene_, character_);
    return anim::samplePose(character_, &clip, scene::clipTimeAt(scene_, character_, time),
                            anim::Wrap::Clamp);
}

void SceneSimulation::addPass(const std::string& name, uint32_t dispatches) {
    for (PassRecord& p : recorded_)
        if (p.name == name) {
            p.dispatches += dispatches;
            return;
        }
    recorded_.push_back({name, dispatches, 0.0});
}

void SceneSimulation::recordFrame(VkCommandBuffer cmd, uint32_t frame) {
    currentFrame_ = frame;
    recorded_.clear();
    const float t = frameTime(frame);
    framePose_ = poseAt(t);
    const anim::Pose& pose = framePose_;
    timer_.reset(cmd);
    // The drawn effects: one segment per frame.
    for (TrajectoryEffect& effect : trajectories_) {
        if (effect.spec->type == scene::EffectType::Smoke) continue;
        effect.live = effectLive(*effect.spec, t);
        if (!effect.live) {
            effect.queue->skip(t);
            continue;
        }
        const std::string name =
            effect.spec->name + "/" + trajectory::methodName(effect.queue->options().method);
        timer_.begin(cmd, name);
        effect.queue->record(
            cmd, trajectory::sourcePalette(character_, effect.source, pose, placement()), t);
        timer_.end(cmd);
        addPass(name, 1);
    }
    for (SmokeGrid& grid : grids_)
        recordSmoke(cmd, grid, frame);
}

glm::vec3 SceneSimulation::rootPosition(const anim::Pose& pose) const {
    if (character_.nodes.empty()) return glm::vec3(placement()[3]);
    return glm::vec3(placement() * pose.world[0][3]);
}

// A grid takes stepsPerFrame steps per frame at a fixed rate (steps_per_second rounded up to a
// whole number per frame): step s of the scene ends at s / rate, frame f's last step at f / fps,
// so 30 and 60 frames per second run the same steps. Its smoke effects build their segments at
// the step rate too.
void SceneSimulation::recordSmoke(VkCommandBuffer cmd, SmokeGrid& grid, uint32_t frame) {
    grid.measured = false;
    grid.emittersThisFrame = 0;
    grid.capturedSteps.clear();
    if (grid.follow) {
        // Keep the grid where it was placed relative to the character's root, along the floor
        // (x, z), by whole cells. Awake, the fields move the other way, so the smoke stays put;
        // asleep, there is nothing to carry along.
        const float h = grid.solver->options().grid.cellSize;
        glm::vec3 moved = rootPosition(framePose_) - grid.rootAtPlacement;
        moved.y = 0.0f;
        const glm::ivec3 cells =
            glm::ivec3(glm::round((grid.placedOrigin + moved - grid.origin) / h));
        if (cells != glm::ivec3(0)) {
            if (grid.awake) {
                grid.solver->recordShift(cmd, cells);
                addPass(grid.name + "/shift", 0);
            }
            grid.origin += glm::vec3(cells) * h;
        }
    }
    const uint32_t n = grid.stepsPerFrame;
    const float rate = scene_.output.fps * float(n);
    bool anyLiveThisFrame = false;
    for (uint32_t k = 0; k < n; ++k) {
        const int64_t step = int64_t(frame) * n + k - (n - 1);
        if (step < 0) continue;
        const float t = float(step) / rate;
        bool anyLive = false;
        // The frame's last step is at the frame's time, whose pose recordFrame already has.
        const anim::Pose stepPose = k + 1 == n ? anim::Pose{} : poseAt(t);
        const anim::Pose& pose = k + 1 == n ? framePose_ : stepPose;
        for (size_t i : grid.effects) {
            TrajectoryEffect& effect = trajectories_[i];
            effect.live = effectLive(*effect.spec, t);
            if (!effect.live) {
                effect.queue->skip(t);
                continue;
            }
            anyLive = true;
            const std::string name = grid.name + "/" + effect.spec->name + "/" +
                                     trajectory::methodName(effect.queue->options().method);
            timer_.begin(cmd, name);
            effect.queue->record(
                cmd, trajectory::sourcePalette(character_, effect.source, pose, placement()), t);
            timer_.end(cmd);
            addPass(name, 1);
        }
        anyLiveThisFrame = anyLiveThisFrame || anyLive;
        if (anyLive) grid.awake = true;
        if (!grid.awake) continue;
        uint32_t emitters = 0;
        for (size_t i : grid.effects) {
            const TrajectoryEffect& effect = trajectories_[i];
            if (!effect.live) continue;
            fluid::CouplingParameters parameters;
            parameters.gridOrigin = grid.origin;
            parameters.radius = effect.spec->radius;
            parameters.strength = effect.spec->strength;
            parameters.maxEmitters = effect.spec->maxEmitters;
            parameters.samplesPerVertex = effect.spec->subSamples + 1;
            const std::string name = grid.name + "/" + effect.spec->name + "/segment_emitters";
            timer_.begin(cmd, name);
            emitters += coupling_->record(
                cmd, effect.queue->vertices(), effect.queue->newestSegment().firstVertex,
                effect.queue->verticesPerSegment(), grid.emitters, emitters, parameters);
            timer_.end(cmd);
            addPass(name, 1);
        }
        grid.emittersThisFrame += emitters;
        if (grid.captured) captureStep(cmd, grid, uint64_t(step), emitters);
        grid.solver->setEmitterBuffer(grid.emitters, emitters);
        timer_.setPrefix(grid.name + "/");
        grid.solver->recordStep(cmd, &timer_);
        timer_.setPrefix("");
        for (const auto& [stage, count] : grid.solver->lastStepDispatches())
            addPass(grid.name + "/" + stage, count);
    }
    if (grid.awake && !anyLiveThisFrame) {
        const std::string name = grid.name + "/measure_activity";
        timer_.begin(cmd, name);
        grid.solver->recordMeasureActivity(cmd, grid.activity);
        timer_.end(cmd);
        addPass(name, 1);
        grid.measured = true;
    }
}

void SceneSimulation::setCaptureEmitters(bool capture) {
    for (SmokeGrid& grid : grids_) {
        grid.capturedSteps.clear();
        grid.captured =
            capture ? gpu::createBuffer(ctx_, grid.emitters.size * grid.stepsPerFrame,
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                        gpu::MemoryUsage::Readback, "captured smoke emitters")
                    : gpu::Buffer{};
    }
}

// Copies the records segment_emitters just wrote into the step's slot of the capture buffer. The
// splat reads them after this, and the next step's segment_emitters overwrites them only after
// the copy has read them.
void SceneSimulation::captureStep(VkCommandBuffer cmd, SmokeGrid& grid, uint64_t step,
                                  uint32_t count) {
    const uint32_t slot = uint32_t(grid.capturedSteps.size());
    grid.capturedSteps.push_back({step, count});
    if (count == 0) return;
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                       VK_ACCESS_2_TRANSFER_READ_BIT);
    const VkBufferCopy region{0, VkDeviceSize(slot) * grid.emitters.size,
                              VkDeviceSize(count) * sizeof(shared::FluidEmitter)};
    vkCmdCopyBuffer(cmd, grid.emitters.get(), grid.captured.get(), 1, &region);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_HOST_READ_BIT);
}

std::vector<CapturedStep> SceneSimulation::capturedEmitters(size_t grid) const {
    std::vector<CapturedStep> out;
    if (grid >= grids_.size() || !grids_[grid].captured) return out;
    const SmokeGrid& g = grids_[grid];
    const auto* bytes = static_cast<const std::byte*>(g.captured.mapped);
    for (size_t slot = 0; slot < g.capturedSteps.size(); ++slot) {
        CapturedStep step;
        step.step = g.capturedSteps[slot].first;
        step.emitters.resize(g.capturedSteps[slot].second);
        std::memcpy(step.emitters.data(), bytes + slot * g.emitters.size,
                    step.emitters.size() * sizeof(shared::FluidEmitter));
        out.push_back(std::move(step));
    }
    return out;
}

SimulationFrameStats SceneSimulation::finishFrame() {
    SimulationFrameStats stats;
    stats.frame = currentFrame_;
    stats.time = frameTime(currentFrame_);
    stats.passes = recorded_;
    for (const gpu::PassTime& t : timer_.results())
        for (PassRecord& p : stats.passes)
            if (p.name == t.name) {
                p.gpuMs += t.milliseconds;
                break;
            }
    for (SmokeGrid& grid : grids_) {
        GridFrameState state;
        state.name = grid.name;
        state.awake = grid.awake;
        state.emitters = grid.emittersThisFrame;
        state.measured = grid.measured;
        if (grid.awake) ++stats.awakeGrids;
        if (grid.measured) {
            uint32_t bits[2];
            std::memcpy(bits, grid.activity.mapped, sizeof bits);
            std::memcpy(&state.largestAlpha, &bits[0], 4);
            std::memcpy(&state.largestSpeed, &bits[1], 4);
            const fluid::GridShape& shape = grid.solver->options().grid;
            const float speedThreshold =
                grid.sleepThreshold * shape.cellSize / grid.solver->options().dt;
            if (state.largestAlpha < grid.sleepThreshold && state.largestSpeed < speedThreshold)
                grid.awake = false;
        }
        stats.grids.push_back(state);
    }
    stats.fluidBytes = fluidBytes();
    return stats;
}

SimulationFrameStats SceneSimulation::runFrame(uint32_t frame) {
    gpu::submitOneShot(ctx_, [&](VkCommandBuffer cmd) { recordFrame(cmd, frame); });
    return finishFrame();
}

uint64_t SceneSimulation::fluidBytes() const {
    uint64_t bytes = 0;
    for (const SmokeGrid& grid : grids_)
        bytes += grid.solver->memoryBytes() + grid.emitters.size + grid.activity.size;
    return bytes;
}

} // namespace mfx::sim
