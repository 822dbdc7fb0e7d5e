// A scene's motion and smoke, frame by frame, on the GPU: only what the scene's effects call for.
//
//   * every effect follows one character of the scene's cast (its "character"; the first by
//     default): its vertices, poses and placement are that character's;
//   * every effect whose kind has a trail (core/scene/effect_spec.h) gets a trajectory queue over
//     the vertices its bones and meshes select (speed-lines: lines, blur: volumes, particles:
//     points, smoke: the newest segment only); outside its time window an effect writes no
//     segment and its trail ages out; kinds without a trail keep their history in their pass;
//   * smoke effects with the same grid settings share one grid (fluid/smoke_grid.h: its
//     placement, follow, step and sleep); no smoke effect, no grid: no fluid memory and no
//     fluid dispatch;
//   * a grid steps at a fixed rate (steps_per_second, rounded up to whole steps per frame), and
//     its smoke effects build their segments at that rate, so 30 and 60 frames per second
//     simulate the same smoke;
//   * each step every live smoke effect's newest segment becomes emitters on the GPU
//     (segment_emitters: impulse velocity, colour as pigment, strength by attenuation), in the
//     grid's own frame; the grid is placed around the effects' vertices over their windows;
//   * a grid none of whose effects is live keeps stepping while its smoke settles, until it
//     sleeps (SmokeGrid::finishFrame);
//   * a sparse grid ("domain": "sparse") stands still, centred like a dense one, over a virtual
//     domain (the stage), and steps only the bricks with smoke: smoke left behind stays.
// Statistics per frame: every pass that ran, with its dispatches and GPU milliseconds, and the
// fluid memory.
#pragma once

#include "core/anim/body_capsules.h"
#include "core/gpu/resources.h"
#include "core/gpu/timer.h"
#include "core/scene/kinds/smoke_effect.h"
#include "core/scene/scene.h"
#include "core/trajectory/surface_source.h"
#include "core/trajectory/trajectory_queue.h"
#include "fluid/segment_emitters.h"
#include "fluid/smoke_grid.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace mfx::sim {

struct PassRecord {
    std::string name;
    uint32_t dispatches = 0;
    double gpuMs = 0.0;
};

struct GridFrameState {
    std::string name;
    bool awake = false;        // stepped this frame
    uint32_t emitters = 0;     // splatted this frame
    bool measured = false;     // measured its activity (no effect live)
    float largestAlpha = 0.0f; // when measured
    float largestSpeed = 0.0f; // when measured, world units per second (dense grids)
    // "collide": the solids (body capsules) of the frame's last step and the cells they fill.
    uint32_t solids = 0;
    uint64_t solidCells = 0;
    // A sparse grid: its active and refused bricks after the frame's last rebuild, and, on the
    // first frame that wanted more bricks than its budget, the line that says so.
    bool sparse = false;
    uint32_t activeBricks = 0;
    uint32_t refusedBricks = 0;
    std::string budgetLine;
};

// The emitter records one smoke step splatted (SceneSimulation::capturedEmitters).
struct CapturedStep {
    uint64_t step = 0; // the grid's step number in the scene: it ends at step / steps per second
    std::vector<shared::FluidEmitter> emitters; // in the grid's frame, as the splat read them
};

struct SimulationFrameStats {
    uint32_t frame = 0;
    float time = 0.0f;
    std::vector<PassRecord> passes; // in recording order, one per name
    uint64_t fluidBytes = 0;        // GPU memory of every smoke grid
    uint32_t awakeGrids = 0;        // grids that stepped this frame
    std::vector<GridFrameState> grids;
    uint32_t dispatches() const;
    uint32_t fluidDispatches() const; // of passes whose name starts with "smoke"
};

class SceneSimulation {
public:
    struct TrajectoryEffect {
        const scene::EffectSpec* spec = nullptr;
        const scene::TrailSpec* trail = nullptr; // its kind's trail (never null)
        const scene::SmokeSpec* smoke = nullptr; // its kind's settings for smoke, else null
        size_t character = 0;                    // the cast member it follows
        trajectory::Source source;
        std::unique_ptr<trajectory::Queue> queue;
        bool live = false;                 // wrote a segment this frame
        trajectory::SurfaceReport surface; // for smoke emitted from the surface
    };
    // A smoke grid (fluid/smoke_grid.h: placement, follow, step, sleep) and the smoke effects
    // that feed it.
    struct SmokeGrid {
        explicit SmokeGrid(fluid::SmokeGrid g) : grid(std::move(g)) {}
        fluid::SmokeGrid grid;
        std::vector<size_t> effects; // indices into trajectories()
        uint32_t emittersThisFrame = 0;
        // With setCaptureEmitters(true): a read-back copy of every step's emitter records, one
        // slot of the emitter buffer's size per step of the frame, and the step and record count
        // of each slot.
        gpu::Buffer captured;
        std::vector<std::pair<uint64_t, uint32_t>> capturedSteps;
        // "collide": each character's body capsules the smoke flows around (by cast member; all
        // empty: none), the smallest thickness, and the poses of the last step (the solids'
        // velocities are their motion since).
        std::vector<std::vector<anim::BodyCapsule>> capsules;
        float collideThickness = 0.0f;
        std::vector<anim::Pose> lastStepPoses;
        bool collides() const {
            return std::any_of(capsules.begin(), capsules.end(),
                               [](const auto& c) { return !c.empty(); });
        }
        std::vector<shared::FluidSolid> lastSolids; // the last step's, in the grid's coordinates
    };

    // The cast has one character per scene.characters entry, in its order, and must outlive the
    // simulation.
    static Result<std::unique_ptr<SceneSimulation>> create(const gpu::Context& ctx,
                                                           const scene::Scene& scene,
                                                           std::span<const anim::Character> cast);
    static Result<std::unique_ptr<SceneSimulation>>
    create(const gpu::Context& ctx, const scene::Scene& scene, const anim::Character& character) {
        return create(ctx, scene, std::span<const anim::Character>(&character, 1));
    }

    const scene::Scene& scene() const { return scene_; }
    std::span<const anim::Character> cast() const { return cast_; }
    const anim::Character& character(size_t c = 0) const { return cast_[c]; }
    // The index in scene().effects of a trajectory effect's spec.
    size_t effectIndex(const TrajectoryEffect& effect) const {
        return size_t(effect.spec - scene_.effects.data());
    }
    uint32_t frameCount() const { return frames_; }
    float frameTime(uint32_t frame) const { return float(frame) / scene_.output.fps; }
    // The frame last recorded (recordFrame's), 0 before the first.
    uint32_t recordedFrame() const { return currentFrame_; }

    // Records frame `frame`; frames are recorded in order, each after the previous one finished.
    // With `pose` (a host's animation: every node's world matrix, before placement()), the first
    // character is in that pose at the frame instead of its clip's, and a grid's steps between
    // the previous frame and this one take the poses between the two (anim::interpolatePose); the
    // previous frame's pose is the clip's when it had none. The other characters play their clips.
    void recordFrame(VkCommandBuffer cmd, uint32_t frame, const anim::Pose* pose = nullptr);
    // After the frame's submission has finished: its statistics (and the sleep decisions).
    SimulationFrameStats finishFrame();
    // recordFrame, submit, wait, finishFrame.
    SimulationFrameStats runFrame(uint32_t frame);

    // Where character `c` stands, and its pose at a scene time (for drawing it).
    glm::mat4 placement(size_t c = 0) const;
    anim::Pose poseAt(size_t c, float time) const;
    // Its first node, in the world, in `pose`.
    glm::vec3 rootPosition(size_t c, const anim::Pose& pose) const;
    // Character `c`'s pose at the frame last recorded (what a renderer draws with it).
    const anim::Pose& framePose(size_t c = 0) const { return framePoses_[c]; }
    std::span<const anim::Pose> framePoses() const { return framePoses_; }
    std::vector<glm::mat4> placements() const; // of every character

    // Emitter capture, for replaying a scene's impulses in another solver run (fluid/
    // scene_scenario.h). A grid's emitter buffer is rewritten by every step, so when a frame takes
    // several steps, reading it after the frame gives the last step's records only; with capture
    // on, each step also copies its records into a read-back buffer. Off by default (it costs a
    // copy per step and a buffer per grid). Takes effect from the next recordFrame.
    void setCaptureEmitters(bool capture);
    // After finishFrame, with capture on: what every step grid `grid` ran this frame splatted, in
    // step order (steps skipped while the grid slept are absent; a step with no live effect has
    // no records).
    std::vector<CapturedStep> capturedEmitters(size_t grid) const;

    // Whether scene time `time` is inside effect `e`'s window (half a frame of slack at each end,
    // so a boundary on a frame time is inside it).
    bool effectLive(const scene::EffectSpec& e, float time) const;

    const std::vector<TrajectoryEffect>& trajectories() const { return trajectories_; }
    const std::vector<SmokeGrid>& smokeGrids() const { return grids_; }
    // Non-const for reading a grid's fields back (SmokeSolver::state records a copy).
    std::vector<SmokeGrid>& smokeGrids() { return grids_; }
    uint64_t fluidBytes() const;
    // Different for every simulation this process creates: a pass that keeps a history of frames
    // (FrameHistory, render/effect_geometry.h) knows from it when a restarted view began a new
    // simulation.
    uint64_t serial() const { return serial_; }

private:
    SceneSimulation(const gpu::Context& ctx, scene::Scene scene,
                    std::span<const anim::Character> cast)
        : ctx_(ctx), scene_(std::move(scene)), cast_(cast) {}
    static uint64_t nextSerial() {
        static std::atomic<uint64_t> counter{0};
        return ++counter;
    }
    void addPass(const std::string& name, uint32_t dispatches);
    void recordSmoke(VkCommandBuffer cmd, SmokeGrid& grid, uint32_t frame);
    void captureStep(VkCommandBuffer cmd, SmokeGrid& grid, uint64_t step, uint32_t count);
    uint32_t recordBursts(VkCommandBuffer cmd, SmokeGrid& grid, float from, float to,
                          uint32_t first);
    void placeGrid(SmokeGrid& grid);

    const gpu::Context& ctx_;
    scene::Scene scene_;
    std::span<const anim::Character> cast_;
    uint64_t serial_ = nextSerial();
    uint32_t frames_ = 0;
    std::vector<TrajectoryEffect> trajectories_;
    std::vector<SmokeGrid> grids_;
    std::unique_ptr<fluid::SegmentEmitters> coupling_;
    gpu::GpuTimer timer_;
    std::vector<PassRecord> recorded_; // names and dispatches of this frame's passes
    uint32_t currentFrame_ = 0;
    std::vector<anim::Pose> framePoses_; // by cast member
    anim::Pose previousPose_;            // the first's previous frame, for a given pose's steps
    bool givenPose_ = false;             // framePoses_[0] came from recordFrame's caller
};

} // namespace mfx::sim
