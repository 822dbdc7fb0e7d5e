// The smoke solver on the GPU: a 3D MAC grid in storage images, one compute shader per stage
// (shaders/fluid/<stage>.comp), the same stages and discretisation as the CPU reference
// (fluid/reference/), written down in docs/fluid.md. One sub-step:
//
//   splatImpulses → advectVelocity → advectPigment → applyBuoyancy → vorticityConfinement →
//   applyTurbulence → diffuseViscosity → computeDivergence → solvePressure → project
//
// (applyBoundaries runs alone only: the stages keep the faces as the boundaries want them;
// fluid/stage_table.h.)
//
// solvePressure runs Jacobi sweeps here (shaders/fluid/solve_pressure.comp), or red-black
// Gauss-Seidel, multigrid or MGPCG (fluid/gpu_multigrid.h), as SolverOptions::pressureSolver asks.
//
// The fields are a SmokeFields (fluid/smoke_fields.h): r32f / rgba32f 3D storage images in GENERAL
// layout. A stage that rewrites a whole field stores it by the store path
// (SolverOptions::storePath): on a CPU driver into a storage buffer, then copied into the image
// (its image stores are costly), on a GPU straight into the image; docs/fluid.md, "Grid". Velocity
// and pigment are ping-ponged between image sets, and the stages are separated by memory barriers.
// The stages themselves are the stage table's (fluid/stage_table.h), their programs the kernel
// table's (fluid/stage_programs.h); each stage below binds its resources as it records
// (core/gpu/program.h).
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/gpu/timer.h"
#include "fluid/gpu_multigrid.h"
#include "fluid/grid_solver.h"
#include "fluid/smoke_fields.h"
#include "fluid/solver_options.h"
#include "fluid/stage_programs.h"

#include <array>
#include <initializer_list>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace mfx::gpu {
class Context;
}

namespace mfx::fluid {

// Whether stages store whole fields straight into their images on `ctx`'s device: `path`, with
// Auto resolved by the device (Buffer on a CPU device, Direct on any other).
bool storesDirect(StorePath path, const gpu::Context& ctx);
// Whether the stages that read solids are split into the blocks away from and near them on
// `ctx`'s device (SolverOptions::solidLists; Auto: on a CPU device).
bool splitsSolids(ByDevice choice, const gpu::Context& ctx);

class SmokeSolver final : public GridSolver {
public:
    // Fails when the options are invalid or the grid exceeds the device's 3D image size.
    static Result<std::unique_ptr<SmokeSolver>> create(const gpu::Context& ctx,
                                                       const SolverOptions& options);
    SmokeSolver(const SmokeSolver&) = delete;
    SmokeSolver& operator=(const SmokeSolver&) = delete;

    const SolverOptions& options() const override { return options_; }
    // Whether stages store whole fields straight into their images (SolverOptions::storePath).
    bool storesDirect() const { return direct_; }
    // The current pigment field (rgba32f or rgba16f, GENERAL layout, sampled usage): what a
    // renderer draws.
    PigmentVolume pigmentVolume() const override;

    // Uploads / reads back every field (waits for the GPU).
    void setState(const FieldState& state);
    FieldState state() override;
    std::vector<uint8_t> storedCells() const override; // every cell

    // Emitters for the following steps, copied into the solver's own buffer after validation.
    Status setEmitters(std::span<const shared::FluidEmitter> emitters);
    // Emitters read from a GPU buffer filled by other GPU work (e.g. trajectory segments):
    // `count` records of shared::FluidEmitter. Not checked on the CPU; the splat shader ignores
    // records with a non-finite position, radius or strength.
    void setEmitterBuffer(const gpu::Buffer& buffer, uint32_t count) override;

    // The moving solids of the sub-steps from now on (capsules where the step ends, with their
    // ends' velocities; docs/fluid.md, "Solids"), copied into the solver's own buffer after
    // validation; an empty list removes them. Each sub-step's mark_solids stage puts them into
    // the grid (so the fields show them after the next step, or runStage(Stage::MarkSolids)); the
    // solids are copied into each recording, so steps recorded one after another may each have
    // their own. Refused naming why as validateGpuSolids and validateSolidOptions refuse them.
    Status setSolids(std::span<const shared::FluidSolid> solids) override;
    bool hasSolids() const { return !solids_.empty(); }
    // Whether the stages that read solids are dispatched split into the blocks away from and near
    // them (SolverOptions::solidLists resolved for the device, with solids set).
    bool splitsSolidStages() const { return splitSolids_ && !solids_.empty(); }
    // The most solids a step takes.
    static constexpr size_t kMaxSolids = kMaxGpuSolids;

    // Records one whole step (all sub-steps) into `cmd`. With a timer, each stage is a pass
    // named after it (stageName()), once per sub-step. The parameters uniform is written now,
    // so the previous recording must have finished executing.
    void recordStep(VkCommandBuffer cmd, gpu::GpuTimer* timer = nullptr);
    // Records one stage alone (with the sub-step dt).
    void recordStage(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer = nullptr);
    // Seconds of simulation the recorded steps have covered (recordStep adds dt after recording):
    // the turbulence's noise time. A stage recorded alone reads it and leaves it.
    double time() const { return time_; }
    void setTime(double seconds) { time_ = seconds; }

    // Convenience: record, submit and wait.
    void step();
    void runStage(Stage stage);

    // The compute dispatches of each stage in the last recordStep(), in step order, and GPU
    // memory of the fields and buffers.
    const StageDispatches& lastStepDispatches() const { return lastStepDispatches_; }
    uint64_t memoryBytes() const override;
    // Sweeps, V-cycles or CG iterations of the last pressure solve (MGPCG stops early on its
    // tolerance: read back from the GPU, so the step must have finished).
    uint32_t lastPressureIterations() const;

    // Records measure_activity: the largest pigment alpha and the largest cell-centre speed of
    // the current fields into `out` (two floats as uint bits, cleared first), for deciding whether
    // the smoke has settled. `out` needs STORAGE_BUFFER and TRANSFER_DST usage. One dispatch.
    uint32_t recordMeasureActivity(VkCommandBuffer cmd, const gpu::Buffer& out,
                                   gpu::GpuTimer* timer = nullptr) override;
    // Settled when the measured alpha and speed are below the rules' thresholds.
    SolverActivity finishFrame(const gpu::Buffer& activity, bool measured, bool stepped,
                               const SettleRules& rules) override;
    // The scene's step is the step: the dense grid has no bricks to rebuild.
    void recordSceneStep(VkCommandBuffer cmd, const SettleRules&, gpu::GpuTimer* timer) override {
        recordStep(cmd, timer);
    }
    StageDispatches lastScenePasses() const override { return lastStepDispatches_; }

    // Records a move of the grid by whole cells: afterwards field(q) holds what field(q + cells)
    // held (velocity, pigment and pressure), and what comes in from outside is 0. For a grid that
    // follows a character: the smoke stays where it was in the world.
    bool recordShift(VkCommandBuffer cmd, glm::ivec3 cells) override {
        fields_.recordShift(cmd, cells);
        return true;
    }

    // Upper bound of timer passes one recordStep() makes.
    uint32_t passesPerStep() const { return uint32_t(stepOrder().size()) * options_.substeps; }

private:
    // The stage table (fluid/stage_table.h) names the stage functions below.
    friend std::span<const StageEntry> stageTable();

    using Writes = std::vector<gpu::DescriptorWrite>;

    SmokeSolver(const gpu::Context& ctx, const SolverOptions& options);
    void writeParameters();
    void recordStageOnly(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer);
    // Records, after the dispatches that wrote whole fields, what makes them visible to what
    // follows: with `direct` (they stored into the images) a barrier; else the copies of the
    // fields they wrote x-fastest into buffers into their images, between barriers.
    void storeFields(VkCommandBuffer cmd, bool direct,
                     std::initializer_list<std::pair<const gpu::Buffer*, gpu::Image*>> fields);
    // Binds `program` with `writes` and dispatches it over `extent` items.
    void dispatch(VkCommandBuffer cmd, gpu::Program& program,
                  std::span<const gpu::DescriptorWrite> writes, glm::uvec3 extent) const;
    // A stage's program, as StagePrograms::get names it.
    struct StageProgram {
        std::string_view name;
        uint32_t target = 0;
        uint32_t variant = 0;
        bool direct = false;
    };
    // A stage that reads the solids, over `extent` items (the cells, the faces of a component or
    // the cells + 1): one dispatch, or where the solids split it (splitSolids_) two indirect
    // ones, over the blocks away from solids and over those near them (fluid_solids.glsl).
    void dispatchStage(VkCommandBuffer cmd, const StageProgram& program,
                       std::span<const gpu::DescriptorWrite> writes, glm::uvec3 extent);
    // `writes` and, for each binding of shaders/fluid/fluid_solids.glsl that `program` declares
    // and `writes` does not write: the flags (15), the blocks' words (19), block list `list`'s
    // window (21; 0: a buffer that no workgroup reads) and the stencils' solid corners (22), or
    // before any solid a small buffer in their place. Every bind of a program that includes
    // fluid_solids.glsl goes through it.
    Writes withSolidBindings(std::span<const gpu::DescriptorWrite> writes,
                             const gpu::Program& program, uint32_t list) const;
    // Workgroup-sized blocks over the cells + 1 (fluid_solids.glsl), and Jacobi bricks, per axis.
    glm::uvec3 solidBlockGrid() const;
    glm::uvec3 solidBrickGrid() const;
    uint32_t solidBlockCount() const;
    uint32_t solidBrickCount() const;
    // The block lists and brick lists as if no cell were near a solid (before the first mark).
    void uploadEmptySolidLists();
    // The parameters uniform at binding 0, then the three components of velocity image set `set`
    // at bindings 1-3 (the layout of most stages).
    Writes withVelocity(int set) const;

    void markSolids(VkCommandBuffer cmd);
    // mark_solids' passes 2 and 5: the blocks' and bricks' words from the flags, then their lists.
    void makeSolidLists(VkCommandBuffer cmd, std::span<const gpu::DescriptorWrite> writes);
    void splatImpulses(VkCommandBuffer cmd);
    std::vector<uint32_t> advectionPasses() const;
    void advectVelocity(VkCommandBuffer cmd);
    void advectPigment(VkCommandBuffer cmd);
    void applyBuoyancy(VkCommandBuffer cmd);
    void vorticityConfinement(VkCommandBuffer cmd);
    void applyTurbulence(VkCommandBuffer cmd);
    void applyVorticityForce(VkCommandBuffer cmd); // its last pass
    void diffuseViscosity(VkCommandBuffer cmd);
    void applyBoundaries(VkCommandBuffer cmd);
    void computeDivergence(VkCommandBuffer cmd);
    void solvePressure(VkCommandBuffer cmd);
    void project(VkCommandBuffer cmd);

    const gpu::Context& ctx_;
    SolverOptions options_;
    SmokeFields fields_;
    StagePrograms programs_;
    std::unique_ptr<GpuMultigrid> multigrid_; // every pressure solver but Jacobi
    bool direct_ = false;                     // options.storePath resolved for the device
    bool fusedVorticity_ = false;             // the direct path's one-dispatch curl and force
    bool splitSolids_ = false;                // options.solidLists resolved for the device
    // Recording a step (not a stage alone): the divergence pass may do the Jacobi solve's first
    // sweep (SolverOptions::firstSweepInDivergence); firstSweepDone_ tells solvePressure where it
    // went: 0 not done, 1 packedPressure[1], 2 the other pressure image (compute_divergence.comp's
    // kFirstSweep).
    bool stepping_ = false;
    uint32_t firstSweepDone_ = 0;

    gpu::Buffer parameters_;
    gpu::Buffer ownEmitters_;
    VkBuffer emitterBuffer_ = VK_NULL_HANDLE;
    VkDeviceSize emitterBufferSize_ = 0;
    uint32_t emitterCount_ = 0;
    double time_ = 0.0; // time()
    // applyTurbulence: the noise's potential on every edge, one vec4 per grid corner (made on
    // first use).
    gpu::Buffer turbulencePotential_;
    gpu::Buffer splatRegions_;               // SplatRegion per target, written by emitter_bounds
    std::vector<shared::FluidSolid> solids_; // what markSolids records
    gpu::Buffer solidsBuffer_;               // where it records them (kMaxSolids; once solids come)
    gpu::Buffer solidBoxBlocks_;             // mark_solids' first pass's blocks (likewise)
    gpu::Buffer solidCells_;                 // a flag byte per cell (fluid_solids.glsl; likewise)
    gpu::Buffer solidCorners_;               // a stencil's solid corners per cell (likewise)
    gpu::Buffer solidHolders_; // per cell, which solid holds it (mark_solids.comp; likewise)
    gpu::Buffer solidBits_;    // per cell, whether a solid holds it (likewise)
    gpu::Buffer solidBricks_;  // per Jacobi brick, whether solids are near; the lists (likewise)
    gpu::Buffer solidBlocks_;  // per workgroup-sized block, whether solids are near; the lists
    gpu::Buffer solidLists_;   // the block lists (fluid_solids.glsl; where the stages are split)
    gpu::Buffer noSolidCells_; // bound in its place before any solid
    gpu::Buffer noSolidList_;  // bound as binding 21 where no block list is walked

    mutable uint32_t dispatches_ = 0; // vkCmdDispatch calls recorded so far
    StageDispatches lastStepDispatches_;
};

} // namespace mfx::fluid
