// What a smoke grid (fluid/smoke_grid.h) and the smoke pass (render/smoke_pass.h) ask of a solver,
// whichever domain it solves on: the dense grid (fluid/smoke_solver.h) or the sparse one
// (fluid/sparse_smoke_solver.h). The one place that chooses between them is createGridSolver.
#pragma once

#include "core/gpu/resources.h"
#include "core/gpu/timer.h"
#include "core/result.h"
#include "fluid/solver_options.h"
#include "fluid/stage_dispatches.h"

#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace mfx::gpu {
class Context;
}

namespace mfx::fluid {

// The pigment a renderer samples, as the solver stores it.
enum class PigmentLayout {
    Image,      // an rgba32f or rgba16f 3D image in GENERAL layout (image)
    BrickAtlas, // the sparse domain's atlas, brick table and active list (docs/fluid.md)
};
struct PigmentVolume {
    PigmentLayout layout = PigmentLayout::Image;
    const gpu::Image* image = nullptr;
    const gpu::Buffer* atlas = nullptr;      // vec4 per cell, slot s at s * MFX_BRICK_CELLS
    const gpu::Buffer* brickTable = nullptr; // slot per virtual brick, MFX_NO_SLOT where none
    const gpu::Buffer* activeList = nullptr; // BrickListHeader (indirect arguments), the bricks
    // Bytes of pigment the volume holds (what a march over all of it reads).
    uint64_t bytes = 0;
};

// When a grid counts as settled: pigment alpha at most alphaThreshold and (unless it has solids,
// which keep stirring its air while they move) speed at most settleSpeed (world units a second)
// everywhere. The sparse domain keeps a brick while a cell of it has alpha above alphaThreshold
// or moves faster than liveSpeed.
struct SettleRules {
    float alphaThreshold = 1e-4f;
    float settleSpeed = 0.0f;
    float liveSpeed = 0.1f;
};

// What the last frame of a grid measured (finishFrame).
struct SolverActivity {
    bool measured = false; // the largest alpha and speed below were read
    float largestAlpha = 0.0f;
    float largestSpeed = 0.0f; // world units per second
    bool settled = false;      // by the rules: the grid may sleep
    uint32_t activeBricks = 0; // the sparse domain: bricks after the frame's last rebuild
    uint32_t refusedBricks = 0;
    std::string budgetError; // the sparse domain could not grow to what was wanted
};

class GridSolver {
public:
    virtual ~GridSolver() = default;

    virtual const SolverOptions& options() const = 0;
    // The first `count` records of `buffer` (written on the GPU) are the next step's emitters.
    virtual void setEmitterBuffer(const gpu::Buffer& buffer, uint32_t count) = 0;
    // The moving solids of the steps recorded from now on (docs/fluid.md, "Solids"); an error
    // naming why where the solver cannot take them (an empty list it always takes).
    virtual Status setSolids(std::span<const shared::FluidSolid> solids) = 0;
    // One step as a scene runs it (the sparse domain first rebuilds its bricks by the rules).
    // The timer's passes are the stages' names (and "rebuild_bricks").
    virtual void recordSceneStep(VkCommandBuffer cmd, const SettleRules& rules,
                                 gpu::GpuTimer* timer) = 0;
    // The passes of the last recordSceneStep with their dispatches, in order.
    virtual StageDispatches lastScenePasses() const = 0;
    // A frame with no live effect: records what finishFrame needs to judge settling into
    // `activity` (two floats as uint bits), timed as "measure_activity". Returns the dispatches
    // recorded (0, and no pass, where the step's own rebuild measures).
    virtual uint32_t recordMeasureActivity(VkCommandBuffer cmd, const gpu::Buffer& activity,
                                           gpu::GpuTimer* timer) = 0;
    // Once the frame's submission finished: what was measured (`measured`: recordMeasureActivity
    // ran this frame; `stepped`: a step ran).
    virtual SolverActivity finishFrame(const gpu::Buffer& activity, bool measured, bool stepped,
                                       const SettleRules& rules) = 0;
    // Moves the fields by whole cells (a grid that follows a character); false where the domain
    // cannot move.
    virtual bool recordShift(VkCommandBuffer cmd, glm::ivec3 cells) = 0;

    virtual PigmentVolume pigmentVolume() const = 0;
    virtual FieldState state() = 0; // the whole domain, 0 where nothing is stored (waits)
    virtual std::vector<uint8_t> storedCells() const = 0; // 1 per cell that holds values
    virtual uint64_t memoryBytes() const = 0;
};

// The solver of `options`: on the sparse domain with `sparse` (at most maxBricks bricks; the
// options must pass validateSparseOptions), else dense.
struct DomainChoice {
    bool sparse = false;
    uint32_t maxBricks = 4096;
};
Result<std::unique_ptr<GridSolver>>
createGridSolver(const gpu::Context& ctx, const SolverOptions& options, const DomainChoice& domain);

} // namespace mfx::fluid
