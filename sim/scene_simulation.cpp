#include "sim/scene_simulation.h"

#include "core/scene/effect_source.h"
#include "core/scene/kinds/impact_effect.h"
#include "core/scene/scene_fit.h"
#include "core/scene/scene_hits.h"

#include "core/anim/bone_groups.h"
#include "core/anim/sampling.h"
#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "core/trajectory/build_segment.h"
#include "core/trajectory/surface_source.h"
#include "fluid/body_solids.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

namespace mfx::sim {

namespace {

constexpr uint32_t kMaxPasses = 512;
// An impact's burst into the smoke: emitters per hit, and hits a step takes at most.
constexpr uint32_t kBurstEmitters = 7;
constexpr uint32_t kBurstsPerStep = 4;

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

// The one place a scene's smoke keys become a grid's settings and its solver's options: the grid
// of `effects` (smoke effects with equal grid keys; the sleep threshold is their smallest, the
// emitter capacity their sum), stepping at the grid's steps_per_second rounded up to whole steps
// a frame of a scene at `fps`.
fluid::SmokeGridSettings gridSettings(std::span<const scene::SmokeSpec* const> effects, float fps,
                                      std::string name) {
    const scene::SmokeGridSpec& e = effects.front()->grid;
    fluid::SmokeGridSettings settings;
    settings.name = std::move(name);
    settings.follow = e.follow;
    settings.sparse = e.sparse();
    settings.maxBricks = e.maxBricks;
    settings.liveSpeed = e.liveSpeed;
    settings.origin = e.origin;
    settings.sleepThreshold = std::numeric_limits<float>::max();
    settings.emitterCapacity = 0;
    for (const scene::SmokeSpec* effect : effects) {
        const scene::SmokeSpec& smoke = *effect;
        settings.sleepThreshold = std::min(settings.sleepThreshold, smoke.sleepThreshold);
        settings.emitterCapacity += smoke.maxEmitters;
    }
    settings.stepsPerFrame = std::max(1u, uint32_t(std::ceil(e.stepsPerSecond / fps - 1e-4f)));
    fluid::SolverOptions& options = settings.options;
    options.grid = fluid::GridShape{e.cells[0], e.cells[1], e.cells[2], e.cellSize};
    options.dt = 1.0f / (fps * float(settings.stepsPerFrame));
    options.fade = e.fade;
    options.drag = e.drag;
    options.buoyancy = e.buoyancy;
    options.vorticity = e.vorticity;
    options.turbulence = e.turbulence;
    options.turbulenceScale = e.turbulenceScale;
    options.turbulenceSpeed = e.turbulenceSpeed;
    options.jacobiIterations = e.jacobi;
    // The scene's names are the solver's (a test keeps the two lists the same).
    options.pressureSolver = fluid::pressureSolverFromName(e.pressure).value();
    options.advection = fluid::advectionFromName(e.advection).value();
    options.storage = fluid::storageFromName(e.storage).value();
    for (fluid::FaceBoundary& face : options.boundaries)
        face.kind = fluid::Boundary::Open;
    options.boundaries[fluid::FaceLowY].kind = fluid::Boundary::WallFreeSlip; // the stage floor
    return settings;
}

// The body capsules of "collide_bones" (entries as an effect's "bones"); none given: every capsule
// but those of `emitting`, the bones the grid's smoke comes from (smoke born inside a solid would
// be cleared where it is born), and none at all where `wholeBody` emits.
Result<std::vector<anim::BodyCapsule>> collisionCapsules(const anim::Character& character,
                                                         const std::vector<std::string>& bones,
                                                         const std::vector<std::string>& emitting,
                                                         bool wholeBody) {
    std::vector<anim::BodyCapsule> all = anim::fitBodyCapsules(character);
    if (bones.empty()) {
        if (wholeBody) return std::vector<anim::BodyCapsule>{};
        std::erase_if(all, [&](const anim::BodyCapsule& capsule) {
            return std::find(emitting.begin(), emitting.end(),
                             character.nodes[size_t(capsule.node)].name) != emitting.end();
        });
        return all;
    }
    std::vector<std::string> names;
    for (const std::string& entry : bones) {
        auto resolved = anim::resolveBoneEntry(character, entry);
        if (!resolved) return Error{"collide_bones: " + resolved.error().message};
        names.insert(names.end(), resolved.value().begin(), resolved.value().end());
    }
    std::vector<anim::BodyCapsule> chosen;
    for (const anim::BodyCapsule& capsule : all)
        if (std::find(names.begin(), names.end(), character.nodes[size_t(capsule.node)].name) !=
            names.end())
            chosen.push_back(capsule);
    if (chosen.empty())
        return Error{"collide_bones: none of the bones named carries vertices of the body"};
    return chosen;
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

Result<std::unique_ptr<SceneSimulation>>
SceneSimulation::create(const gpu::Context& ctx, const scene::Scene& scene,
                        std::span<const anim::Character> cast) {
    if (cast.size() != scene.characters.size())
        return Error{scene.file + ": " + std::to_string(cast.size()) + " characters given for " +
                     std::to_string(scene.characters.size()) + " in the scene"};
    std::unique_ptr<SceneSimulation> sim(new SceneSimulation(ctx, scene, cast));
    // Bone groups and patterns resolved, automatic bones, strides, camera and stage chosen (a
    // scene the caller fitted already is left as it is).
    if (Status fitted = scene::fitScene(sim->scene_, cast); !fitted) return fitted.error();
    sim->frames_ = scene::frameCount(sim->scene_, cast);
    sim->framePoses_.resize(cast.size());
    for (size_t i = 0; i < sim->scene_.effects.size(); ++i) {
        const scene::EffectSpec& e = sim->scene_.effects[i];
        const std::string where =
            sim->scene_.file + ": effects[" + std::to_string(i) + "] (\"" + e.name + "\"): ";
        TrajectoryEffect effect;
        effect.spec = &e;
        effect.character = scene::effectCharacter(sim->scene_, e);
        const anim::Character& character = cast[effect.character];
        Result<trajectory::Source> selected = scene::effectSource(character, e, &effect.surface);
        if (!selected) return Error{where + selected.error().message};
        // Kinds without a trail keep their own per-vertex history in their pass (the afterimage,
        // swept-volume and silhouette-shell passes, render/effect_geometry.h).
        effect.trail = e.kind().queue();
        if (!effect.trail) continue;
        const scene::TrailSpec& trail = *effect.trail;
        effect.smoke = e.as<scene::SmokeSpec>();
        const bool surface = e.kind().surfaceSampling().has_value();
        if (trail.twoEnds) {
            Result<trajectory::Source> ends = trajectory::twoEnds(character, selected.value());
            if (!ends) return Error{where + ends.error().message};
            effect.source = std::move(ends).value();
        } else {
            effect.source = trail.shape == trajectory::Kind::Volumes || surface
                                ? std::move(selected).value()
                                : strided(selected.value(), trail.stride);
        }
        if (!trail.useMeshColour)
            std::fill(effect.source.colours.begin(), effect.source.colours.end(), trail.colour);
        trajectory::QueueOptions options;
        options.kind = trail.shape;
        options.segment.subSamples = trail.subSamples;
        options.segment.impulseScale = effect.smoke ? effect.smoke->impulseScale : 1.0f;
        options.segment.alphaStart = trail.alphaStart;
        options.segment.alphaEnd = trail.alphaEnd;
        options.segment.alphaPower = trail.alphaPower;
        options.lifetime = trail.lifetime;
        options.maxLifetime = trail.lifetime;
        auto queue = trajectory::Queue::create(ctx, effect.source, options);
        if (!queue) return Error{where + queue.error().message};
        effect.queue = std::move(queue).value();
        sim->trajectories_.push_back(std::move(effect));
    }

    // Smoke effects with the same grid settings share a grid.
    std::vector<std::vector<size_t>> groups;
    for (size_t i = 0; i < sim->trajectories_.size(); ++i) {
        const scene::SmokeSpec* smoke = sim->trajectories_[i].smoke;
        if (!smoke) continue;
        auto shared = std::find_if(groups.begin(), groups.end(), [&](const auto& g) {
            return sim->trajectories_[g.front()].smoke->grid == smoke->grid;
        });
        if (shared != groups.end())
            shared->push_back(i);
        else
            groups.push_back({i});
    }
    for (const std::vector<size_t>& effects : groups) {
        std::vector<const scene::SmokeSpec*> specs;
        for (size_t i : effects)
            specs.push_back(sim->trajectories_[i].smoke);
        fluid::SmokeGridSettings settings = gridSettings(
            specs, sim->scene_.output.fps, "smoke" + std::to_string(sim->grids_.size()));
        // Room for the impacts' bursts (kBurstsPerStep a step).
        if (std::any_of(sim->scene_.effects.begin(), sim->scene_.effects.end(),
                        [](const scene::EffectSpec& e) {
                            const auto* impact = e.as<scene::ImpactSpec>();
                            return impact && impact->smokeImpulse > 0.0f;
                        }))
            settings.emitterCapacity += kBurstsPerStep * kBurstEmitters;
        const std::string name = settings.name;
        auto grid = fluid::SmokeGrid::create(ctx, std::move(settings));
        if (!grid) return Error{sim->scene_.file + ": " + name + ": " + grid.error().message};
        sim->grids_.emplace_back(std::move(grid).value());
        sim->grids_.back().effects = effects;
        const scene::SmokeGridSpec& spec = specs.front()->grid;
        if (spec.collide) {
            // Each character: the capsules its effects in this grid leave free (collide_bones
            // names that character's bones), or every one of a character none of them follows
            // (none where collide_bones picks the bones).
            SmokeGrid& g = sim->grids_.back();
            g.capsules.resize(cast.size());
            for (size_t c = 0; c < cast.size(); ++c) {
                std::vector<std::string> emitting;
                bool wholeBody = false, follows = false;
                for (size_t i : effects) {
                    if (sim->trajectories_[i].character != c) continue;
                    follows = true;
                    const std::vector<std::string>& bones = sim->trajectories_[i].spec->bones;
                    wholeBody = wholeBody || bones.empty();
                    emitting.insert(emitting.end(), bones.begin(), bones.end());
                }
                if (!follows) {
                    if (spec.collideBones.empty()) g.capsules[c] = anim::fitBodyCapsules(cast[c]);
                    continue;
                }
                auto capsules = collisionCapsules(cast[c], spec.collideBones, emitting, wholeBody);
                if (!capsules)
                    return Error{sim->scene_.file + ": " + name + ": " + capsules.error().message};
                g.capsules[c] = std::move(capsules).value();
            }
            g.collideThickness = spec.collideThickness;
        }
        sim->placeGrid(sim->grids_.back());
    }
    if (!sim->grids_.empty()) sim->coupling_ = std::make_unique<fluid::SegmentEmitters>(ctx);
    sim->timer_ = gpu::GpuTimer(ctx, kMaxPasses);
    return sim;
}

glm::mat4 SceneSimulation::placement(size_t c) const {
    return scene::characterPlacement(scene_.characters[c]);
}

std::vector<glm::mat4> SceneSimulation::placements() const {
    std::vector<glm::mat4> out;
    for (size_t c = 0; c < cast_.size(); ++c)
        out.push_back(placement(c));
    return out;
}

bool SceneSimulation::effectLive(const scene::EffectSpec& e, float time) const {
    return scene::effectLive(scene_, e, time);
}

// The grid is centred on the bounds its effects' vertices sweep over their windows (sampled at
// the frame rate, at most scene::kMaxSampledFrames frames an effect), and stands on the floor (y =
// stage.floorHeight) when the stage has one and the bounds allow.
void SceneSimulation::placeGrid(SmokeGrid& grid) {
    glm::vec3 low(std::numeric_limits<float>::max()), high(std::numeric_limits<float>::lowest());
    for (size_t i : grid.effects) {
        const TrajectoryEffect& effect = trajectories_[i];
        const size_t c = effect.character;
        for (uint32_t f : scene::liveSampledFrames(scene_, *effect.spec, frames_)) {
            const anim::Pose pose = poseAt(c, frameTime(f));
            const auto transforms = trajectory::vertexTransforms(
                effect.source,
                trajectory::sourcePalette(cast_[c], effect.source, pose, placement(c)));
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
    // A grid follows the character of its first effect.
    const size_t c = trajectories_[grid.effects.front()].character;
    grid.grid.place(low, high, scene_.characters[c].position,
                    scene_.stage.floor ? std::optional<float>(scene_.stage.floorHeight)
                                       : std::nullopt,
                    rootPosition(c, poseAt(c, frameTime(0))));
}

anim::Pose SceneSimulation::poseAt(size_t c, float time) const {
    return scene::characterPose(scene_, c, cast_[c], time);
}

void SceneSimulation::addPass(const std::string& name, uint32_t dispatches) {
    for (PassRecord& p : recorded_)
        if (p.name == name) {
            p.dispatches += dispatches;
            return;
        }
    recorded_.push_back({name, dispatches, 0.0});
}

void SceneSimulation::recordFrame(VkCommandBuffer cmd, uint32_t frame, const anim::Pose* given) {
    currentFrame_ = frame;
    recorded_.clear();
    const float t = frameTime(frame);
    givenPose_ = given != nullptr;
    if (givenPose_) {
        previousPose_ = framePoses_[0].world.size() == given->world.size()
                            ? std::move(framePoses_[0])
                            : poseAt(0, frame > 0 ? frameTime(frame - 1) : t);
        framePoses_[0] = *given;
    } else {
        framePoses_[0] = poseAt(0, t);
    }
    for (size_t c = 1; c < cast_.size(); ++c)
        framePoses_[c] = poseAt(c, t);
    timer_.reset(cmd);
    // The drawn effects: one segment per frame.
    for (TrajectoryEffect& effect : trajectories_) {
        if (effect.smoke) continue;
        effect.live = effectLive(*effect.spec, t);
        if (!effect.live) {
            effect.queue->skip(t);
            continue;
        }
        const std::string name =
            effect.spec->name + "/" + trajectory::methodName(effect.queue->options().method);
        timer_.begin(cmd, name);
        const size_t c = effect.character;
        effect.queue->record(
            cmd, trajectory::sourcePalette(cast_[c], effect.source, framePoses_[c], placement(c)),
            t);
        timer_.end(cmd);
        addPass(name, 1);
    }
    for (SmokeGrid& grid : grids_)
        recordSmoke(cmd, grid, frame);
}

glm::vec3 SceneSimulation::rootPosition(size_t c, const anim::Pose& pose) const {
    if (cast_[c].nodes.empty()) return glm::vec3(placement(c)[3]);
    return glm::vec3(placement(c) * pose.world[0][3]);
}

// A grid takes stepsPerFrame steps per frame at a fixed rate (steps_per_second rounded up to a
// whole number per frame): step s of the scene ends at s / rate, frame f's last step at f / fps,
// so 30 and 60 frames per second run the same steps. Its smoke effects build their segments at
// the step rate too.
void SceneSimulation::recordSmoke(VkCommandBuffer cmd, SmokeGrid& grid, uint32_t frame) {
    fluid::SmokeGrid& g = grid.grid;
    g.beginFrame();
    grid.emittersThisFrame = 0;
    grid.capturedSteps.clear();
    const size_t followed = trajectories_[grid.effects.front()].character;
    if (g.recordFollow(cmd, rootPosition(followed, framePoses_[followed])))
        addPass(g.name() + "/shift", 0);
    const uint32_t n = g.settings().stepsPerFrame;
    const float rate = scene_.output.fps * float(n);
    bool anyLiveThisFrame = false;
    for (uint32_t k = 0; k < n; ++k) {
        const int64_t step = int64_t(frame) * n + k - (n - 1);
        if (step < 0) continue;
        const float t = float(step) / rate;
        bool anyLive = false;
        // The frame's last step is at the frame's time, whose poses recordFrame already has; the
        // others sample the clips, or blend a given pose with the previous frame's.
        std::vector<anim::Pose> stepPoses;
        if (k + 1 < n) {
            stepPoses.resize(cast_.size());
            for (size_t c = 0; c < cast_.size(); ++c)
                stepPoses[c] = c == 0 && givenPose_
                                   ? anim::interpolatePose(cast_[0], previousPose_, framePoses_[0],
                                                           float(k + 1) / float(n))
                                   : poseAt(c, t);
        }
        const std::vector<anim::Pose>& poses = k + 1 == n ? framePoses_ : stepPoses;
        for (size_t i : grid.effects) {
            TrajectoryEffect& effect = trajectories_[i];
            effect.live = effectLive(*effect.spec, t);
            if (!effect.live) {
                effect.queue->skip(t);
                continue;
            }
            anyLive = true;
            const std::string name = g.name() + "/" + effect.spec->name + "/" +
                                     trajectory::methodName(effect.queue->options().method);
            timer_.begin(cmd, name);
            const size_t c = effect.character;
            effect.queue->record(
                cmd, trajectory::sourcePalette(cast_[c], effect.source, poses[c], placement(c)), t);
            timer_.end(cmd);
            addPass(name, 1);
        }
        anyLiveThisFrame = anyLiveThisFrame || anyLive;
        if (grid.collides()) {
            // The bodies where the step ends, moving as they did since the last step.
            std::vector<shared::FluidSolid> solids;
            for (size_t c = 0; c < cast_.size(); ++c) {
                if (grid.capsules[c].empty()) continue;
                const anim::Pose& before =
                    grid.lastStepPoses.size() == cast_.size() ? grid.lastStepPoses[c] : poses[c];
                const std::vector<shared::FluidSolid> body =
                    fluid::bodySolids(grid.capsules[c], before, poses[c], 1.0f / rate, g.origin(),
                                      grid.collideThickness, placement(c));
                solids.insert(solids.end(), body.begin(), body.end());
            }
            // A pose that is not finite (a host's) has no solids this step.
            grid.lastSolids = g.setSolids(solids) ? solids : std::vector<shared::FluidSolid>{};
            if (grid.lastSolids.empty()) (void)g.setSolids({});
            grid.lastStepPoses = poses;
        }
        // A hit in this step may burst into the smoke (recordBursts): the grid wakes for it.
        const bool hitNow =
            std::any_of(scene_.hits.begin(), scene_.hits.end(), [&](const scene::Hit& h) {
                return h.time > t - 1.0f / rate && h.time <= t;
            });
        if (anyLive || hitNow) g.wake();
        if (!g.awake()) continue;
        uint32_t emitters = 0;
        for (size_t i : grid.effects) {
            const TrajectoryEffect& effect = trajectories_[i];
            if (!effect.live) continue;
            fluid::CouplingParameters parameters;
            parameters.gridOrigin = g.origin();
            parameters.radius = effect.smoke->radius;
            parameters.strength = effect.smoke->strength;
            parameters.maxEmitters = effect.smoke->maxEmitters;
            parameters.samplesPerVertex = effect.trail->subSamples + 1;
            const std::string name = g.name() + "/" + effect.spec->name + "/segment_emitters";
            timer_.begin(cmd, name);
            emitters += coupling_->record(
                cmd, effect.queue->vertices(), effect.queue->newestSegment().firstVertex,
                effect.queue->verticesPerSegment(), g.emitters(), emitters, parameters);
            timer_.end(cmd);
            addPass(name, 1);
        }
        emitters += recordBursts(cmd, grid, t - 1.0f / rate, t, emitters);
        grid.emittersThisFrame += emitters;
        if (grid.captured) captureStep(cmd, grid, uint64_t(step), emitters);
        g.recordStep(cmd, emitters, &timer_);
        for (const auto& [stage, count] : g.lastStepDispatches())
            addPass(g.name() + "/" + stage, count);
    }
    if (g.awake() && !anyLiveThisFrame)
        if (const uint32_t dispatches = g.recordMeasureActivity(cmd, &timer_))
            addPass(g.name() + "/measure_activity", dispatches);
}

// The impacts' smoke bursts of the hits in (from, to]: each hit inside the grid's box pushes the
// air along the blow within its smoke_radius and pigments it, and six emitters around it push it
// outwards across the blow, so the burst opens up (ImpactSpec). Written after the step's segment
// emitters (from `first` on); returns how many.
uint32_t SceneSimulation::recordBursts(VkCommandBuffer cmd, SmokeGrid& grid, float from, float to,
                                       uint32_t first) {
    fluid::SmokeGrid& g = grid.grid;
    const fluid::GridShape& shape = g.options().grid;
    const glm::vec3 size = glm::vec3(shape.cellsX, shape.cellsY, shape.cellsZ) * shape.cellSize;
    std::vector<shared::FluidEmitter> records;
    for (const scene::Hit& hit : scene_.hits) {
        if (!(hit.time > from && hit.time <= to)) continue;
        const scene::ImpactSpec* impact = scene::hitImpact(scene_, hit);
        if (!impact || impact->smokeImpulse <= 0.0f) continue;
        const glm::vec3 p = hit.point - g.origin();
        if (glm::any(glm::lessThan(p, glm::vec3(0.0f))) || glm::any(glm::greaterThan(p, size)))
            continue;
        if (records.size() + kBurstEmitters > size_t(kBurstsPerStep) * kBurstEmitters) break;
        const scene::BlowAxes blow = scene::blowAxes(hit.direction);
        const glm::vec3 axis = blow.along, u = blow.u, v = blow.v;
        const float r = impact->smokeRadius, speed = impact->smokeImpulse;
        // Strong enough to set the air's velocity and pigment within the one step.
        const float strength = 8.0f * scene_.output.fps * float(g.settings().stepsPerFrame);
        records.push_back(
            {glm::vec4(p, r), glm::vec4(axis * speed, strength), impact->smokeColour});
        for (int k = 0; k < 6; ++k) {
            const float a = 6.2831853f * float(k) / 6.0f;
            const glm::vec3 out = u * std::cos(a) + v * std::sin(a);
            records.push_back({glm::vec4(p + out * r, 0.75f * r),
                               glm::vec4((0.6f * out + 0.4f * axis) * speed, strength),
                               impact->smokeColour});
        }
    }
    if (records.empty()) return 0;
    const VkDeviceSize bytes = records.size() * sizeof(shared::FluidEmitter);
    const VkDeviceSize offset = VkDeviceSize(first) * sizeof(shared::FluidEmitter);
    if (offset + bytes > g.emitters().size) return 0;
    // After the previous step's splat read the buffer, before this step's reads it.
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    vkCmdUpdateBuffer(cmd, g.emitters().get(), offset, bytes, records.data());
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    addPass(g.name() + "/impact_bursts", 0);
    return uint32_t(records.size());
}

void SceneSimulation::setCaptureEmitters(bool capture) {
    for (SmokeGrid& grid : grids_) {
        grid.capturedSteps.clear();
        grid.captured =
            capture
                ? gpu::createBuffer(ctx_,
                                    grid.grid.emitters().size * grid.grid.settings().stepsPerFrame,
                                    VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryUsage::Readback,
                                    "captured smoke emitters")
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
    const gpu::Buffer& emitters = grid.grid.emitters();
    const VkBufferCopy region{0, VkDeviceSize(slot) * emitters.size,
                              VkDeviceSize(count) * sizeof(shared::FluidEmitter)};
    vkCmdCopyBuffer(cmd, emitters.get(), grid.captured.get(), 1, &region);
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
        std::memcpy(step.emitters.data(), bytes + slot * g.grid.emitters().size,
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
        state.name = grid.grid.name();
        state.awake = grid.grid.awake(); // before the sleep decision: whether it stepped
        state.emitters = grid.emittersThisFrame;
        if (state.awake) ++stats.awakeGrids;
        const fluid::SmokeGrid::Activity activity = grid.grid.finishFrame();
        state.measured = activity.measured;
        state.largestAlpha = activity.largestAlpha;
        state.largestSpeed = activity.largestSpeed;
        state.sparse = grid.grid.sparse();
        state.activeBricks = activity.activeBricks;
        state.refusedBricks = activity.refusedBricks;
        state.budgetLine = activity.budgetLine;
        state.solids = uint32_t(grid.lastSolids.size());
        state.solidCells = fluid::countSolidCells(grid.grid.options().grid, grid.lastSolids);
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
        bytes += grid.grid.memoryBytes();
    return bytes;
}

} // namespace mfx::sim
