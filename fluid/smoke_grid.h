// A smoke grid standing in the world (Xu et al., section 5; docs/architecture.md, "One frame"):
// one SmokeSolver, where the grid's low corner is, the buffer its emitters are written to, and
// the rules a scene's grid lives by, each a method:
//   * place: centred on the box its effects' vertices sweep, standing on the stage floor when the
//     box allows;
//   * follow: with "follow", it moves with the character's root along the floor (x, z) by whole
//     cells, its fields shifted the other way while awake, so the smoke stays where it is;
//   * step: the solver's step over the emitters written this step; a step wakes the grid;
//   * sleep: a grid none of whose effects is live measures its largest pigment alpha and speed
//     after each frame; once both are below the threshold (speed: threshold x cell size / dt) it
//     sleeps: zero dispatches until an effect is live again.
// The grid holds its solver through fluid/grid_solver.h, dense or sparse alike. A sparse grid
// (settings.sparse: fluid/sparse_smoke_solver.h) stands still over its virtual domain, the stage:
// it rebuilds its active bricks before each step (cells with pigment above the sleep threshold or
// air faster than liveSpeed, the emitters' footprints, one brick of reach around them), so smoke
// stays where it was left; it sleeps once no effect is live and no brick is active, and it holds
// at most maxBricks bricks, the budget (the first frame that wants more gets one line,
// budgetLine). Which effects feed the grid and when is the simulation's business
// (sim/scene_simulation.h).
#pragma once

#include "core/gpu/resources.h"
#include "core/gpu/timer.h"
#include "core/result.h"
#include "fluid/grid_solver.h"

#include <glm/glm.hpp>

#include <memory>
#include <optional>
#include <string>

namespace mfx::fluid {

struct SmokeGridSettings {
    std::string name; // its passes' names start with it ("smoke0/advect_velocity")
    SolverOptions options;
    uint32_t stepsPerFrame = 1;
    bool follow = false;
    float sleepThreshold = 1e-4f;
    uint32_t emitterCapacity = 1; // records one step may splat
    bool sparse = false;          // options.grid is a virtual domain of 8^3 bricks
    uint32_t maxBricks = 4096;    // sparse: the budget of stored bricks
    // Sparse: a brick with no pigment above sleepThreshold stays live while the air in one of its
    // cells moves faster than this (world units a second).
    float liveSpeed = 0.1f;
    // Where the grid's low corner stands in the world, instead of place()'s centring.
    std::optional<glm::vec3> origin;
};

class SmokeGrid {
public:
    static Result<SmokeGrid> create(const gpu::Context& ctx, SmokeGridSettings settings);

    // Centres the grid on the box [low, high] (low > high: no box; it stands centred on
    // `fallback`, its base there), on the floor at `floorHeight` when the box is above it; `root`
    // is where the character's root is now, the origin of follow(). A grid whose settings give
    // its origin stands there instead.
    void place(glm::vec3 low, glm::vec3 high, glm::vec3 fallback, std::optional<float> floorHeight,
               glm::vec3 root);
    // With follow: keeps the grid where it was placed relative to the root, along the floor, by
    // whole cells. Returns whether it recorded a shift of the fields (only while awake: asleep,
    // there is nothing to carry along).
    bool recordFollow(VkCommandBuffer cmd, glm::vec3 root);

    // The frame's bookkeeping: beginFrame before its first step, finishFrame once the frame's
    // submission finished (it reads the measure and decides whether to sleep).
    void beginFrame();
    // A live effect wakes the grid (it steps while awake).
    void wake() { awake_ = true; }
    // One step over the first `emitters` records of emitters(). The timer's passes are prefixed
    // with the grid's name.
    void recordStep(VkCommandBuffer cmd, uint32_t emitters, gpu::GpuTimer* timer);
    // The moving solids of the steps recorded from now on, in the grid's coordinates (origin()
    // at 0): GridSolver::setSolids.
    Status setSolids(std::span<const shared::FluidSolid> solids) {
        return solver_->setSolids(solids);
    }
    // Awake with no effect live this frame: measures the largest pigment alpha and speed.
    // Returns the dispatches it recorded (timed as "<name>/measure_activity"; 0 where the
    // solver's step measures).
    uint32_t recordMeasureActivity(VkCommandBuffer cmd, gpu::GpuTimer* timer);
    // What the solver measured (fluid/grid_solver.h), and the budget's line.
    struct Activity : SolverActivity {
        std::string budgetLine; // the first frame past the budget only
    };
    Activity finishFrame();

    const std::string& name() const { return settings_.name; }
    const SmokeGridSettings& settings() const { return settings_; }
    bool sparse() const { return settings_.sparse; }
    const SolverOptions& options() const { return solver_->options(); }
    // The pigment the smoke pass draws.
    PigmentVolume pigmentVolume() const { return solver_->pigmentVolume(); }
    // The fields (a sparse grid's whole virtual domain, 0 where nothing is stored), read back
    // (waits for the GPU).
    FieldState state() { return solver_->state(); }
    // One flag per cell: 1 where the grid stores values (every cell of a dense grid).
    std::vector<uint8_t> storedCells() const { return solver_->storedCells(); }
    // The passes of the last recordStep with their dispatches (a sparse grid's rebuild first).
    StageDispatches lastStepDispatches() const { return solver_->lastScenePasses(); }
    glm::vec3 origin() const { return origin_; }             // the world position of its low corner
    glm::vec3 placedOrigin() const { return placedOrigin_; } // where place() put it
    bool awake() const { return awake_; }
    const gpu::Buffer& emitters() const { return emitters_; }
    // Its GPU memory: the solver's fields, the emitter and activity buffers.
    uint64_t memoryBytes() const;

private:
    SmokeGridSettings settings_;
    SettleRules rules() const;

    std::unique_ptr<GridSolver> solver_;
    bool stepped_ = false; // a step was recorded this frame
    bool budgetReported_ = false;
    gpu::Buffer emitters_;
    gpu::Buffer activity_; // two floats as uint bits: largest pigment alpha, largest speed
    glm::vec3 origin_{0.0f};
    glm::vec3 placedOrigin_{0.0f};
    glm::vec3 rootAtPlacement_{0.0f};
    bool awake_ = false;
    bool measured_ = false;
};

} // namespace mfx::fluid
