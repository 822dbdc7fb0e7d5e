// The smoke solver on a sparse grid: a virtual domain of bricks of 8^3 cells (fluid/sparse_bricks.h
// says why 8), of which only the active ones are stored, in an atlas of storage buffers
// (shaders/shared/sparse_fluid.h). Every stage is an indirect dispatch over the active bricks
// alone (two workgroups a brick), shaders/fluid/sparse_<stage>.comp, and computes what the dense
// solver computes over the whole virtual domain with every value that is not stored read as 0:
// air at rest, without pigment, at pressure 0 (docs/fluid.md, "Sparse domain"). The CPU reference
// with the same active cells (ReferenceSolver::setActiveCells) is its twin, stage by stage.
//
// The active set is rebuilt on the GPU at the start of each step (recordRebuild): the bricks with
// a live cell (pigment or speed above the sleep thresholds) and those the emitters reach, dilated
// by the advection's reach. Or the caller sets it: want bricks on layout(), then commitActive()
// (the tests; one or the other for a solver's life). Bricks that fall inactive are freed (their
// slots serve the next new ones); new bricks start at rest, except the faces they share with
// bricks active before, which keep their values. The atlas doubles when it runs out of slots, up
// to the budget of bricks given at creation; past it, wanted bricks are refused (counted), never a
// crash, and the simulation goes on with the bricks it has.
//
// Moving solids (setSolids; docs/fluid.md, "Solids") are marked into the stored cells at the start
// of each sub-step (shaders/fluid/sparse_mark_solids.comp), with the dense grid's rules; the
// rebuild wants every brick they may reach, so the body's cells are stored and the air it pushes
// is simulated.
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/gpu/timer.h"
#include "fluid/grid_solver.h"
#include "fluid/solver_options.h"
#include "fluid/sparse_bricks.h"

#include <array>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <tuple>
#include <vector>

namespace mfx::gpu {
class Context;
}

namespace mfx::fluid {

class SparseSmokeSolver final : public GridSolver {
public:
    // options.grid is the virtual domain; the options must pass validateSparseOptions. At most
    // `maxBricks` bricks are stored at once; the atlas starts with `initialSlots`.
    static Result<std::unique_ptr<SparseSmokeSolver>> create(const gpu::Context& ctx,
                                                             const SolverOptions& options,
                                                             uint32_t maxBricks,
                                                             uint32_t initialSlots = 64);
    SparseSmokeSolver(const SparseSmokeSolver&) = delete;
    SparseSmokeSolver& operator=(const SparseSmokeSolver&) = delete;

    const SolverOptions& options() const override { return options_; }

    // The layout: want bricks on it (clearWanted, wantSphere, wantCell, dilate), then commit.
    SparseBricks& layout() { return layout_; }
    const SparseBricks& layout() const { return layout_; }
    // The wanted set becomes the active set, on the GPU too (waits for the GPU): the atlas grows
    // if it must, new bricks start at rest. Not while a recorded step is in flight.
    SparseBricks::Update commitActive();

    // Records the active set's rebuild on the GPU (shaders/fluid/sparse_*_bricks.comp): wanted
    // are the active bricks with a cell whose pigment alpha exceeds `alphaThreshold` or whose
    // cell-centre speed exceeds `speedThreshold` (NaN counts), and the bricks the emitters'
    // spheres reach; then every brick within `reachCells` cells (rounded up to bricks) of a wanted
    // one; then the bricks the solids may reach (SparseBricks::wantCapsule, at the solids set now;
    // not grown: the air they stir is live, and the next rebuild grows its bricks). Unwanted
    // bricks are freed, wanted ones given slots and started at rest. recordStep does not call
    // it: record it before the step.
    void recordRebuild(VkCommandBuffer cmd, float alphaThreshold, float speedThreshold,
                       uint32_t reachCells);
    struct RebuildCounts {
        uint32_t active = 0;      // bricks active after it
        uint32_t activated = 0;   // of which new
        uint32_t refused = 0;     // wanted bricks left inactive: no free slot
        uint32_t livePigment = 0; // half-bricks (8x8x4 cells) of the active set before it with a
                                  // cell whose pigment alpha exceeds the threshold (or NaN, Inf)
        bool grown = false;       // the atlas grew for the refused bricks (active at the next
                                  // rebuild)
        std::string error;        // why it could not grow, when it could not (budget, memory)
    };
    // Once the submission of the last recordRebuild has finished: its counts. If bricks were
    // refused, the atlas grows (doubling, at least to what was wanted, at most to the budget) so
    // that the next rebuild can give them slots; at the budget, or when the device is out of
    // memory, `error` says so and the solver goes on with the slots it has.
    RebuildCounts finishRebuild();
    uint32_t slots() const { return slots_; }
    // The active bricks' indices, ascending, and one flag per virtual cell (1 in an active brick),
    // as the GPU has them (waits for the GPU once it rebuilds the set).
    std::vector<uint32_t> activeBricks() const;
    std::vector<uint8_t> activeCells() const;
    uint32_t maxBricks() const { return layout_.maxBricks(); }

    // The virtual domain's fields, dense (waits for the GPU). setState stores the values of the
    // active bricks and ignores the rest; state() has 0 wherever nothing is stored.
    void setState(const FieldState& state);
    FieldState state() override;
    // Faces stored twice (by two active bricks) whose copies differed in the last state(): 0
    // unless a stage broke the rule that both copies are computed alike.
    uint64_t lastSharedFaceMismatches() const { return sharedFaceMismatches_; }

    Status setEmitters(std::span<const shared::FluidEmitter> emitters);
    // As SmokeSolver::setEmitterBuffer: the first `count` records of `buffer` (written on the GPU,
    // e.g. by SegmentEmitters) are the next rebuild's and step's emitters. The buffer must outlive
    // their recording.
    void setEmitterBuffer(const gpu::Buffer& buffer, uint32_t count) override;
    // As SmokeSolver::setSolids: the moving solids of the sub-steps from now on (each sub-step's
    // mark_solids stage puts them into the stored cells, so the fields show them after the next
    // step, or runStage(Stage::MarkSolids)); copied into each recording; an empty list removes
    // them. Refused naming why as validateGpuSolids refuses them.
    Status setSolids(std::span<const shared::FluidSolid> solids) override;
    bool hasSolids() const { return !solids_.empty(); }
    // The stages of the last recordStep with their dispatch counts, in order (as SmokeSolver's).
    const StageDispatches& lastStepDispatches() const { return lastStepDispatches_; }
    // For drawing the smoke (render/smoke_pass.h): the live pigment atlas (vec4 per cell, slot s
    // at elements s * MFX_BRICK_CELLS + brickCellIndex), the brick table (slot per virtual brick,
    // x fastest, MFX_NO_SLOT where none) and the active list (BrickListHeader, two workgroups of
    // 8x8x4 a brick, then the bricks). Valid until the next step or rebuild is recorded.
    const gpu::Buffer& pigmentAtlas() const { return pigment_[currentPigment_]; }
    const gpu::Buffer& brickTable() const { return table_; }
    const gpu::Buffer& activeList() const { return active_; }

    // As SmokeSolver: one whole step, or one stage alone (with the sub-step dt). Vorticity
    // confinement and viscosity are off on the sparse domain, so those stages record nothing.
    void recordStep(VkCommandBuffer cmd, gpu::GpuTimer* timer = nullptr);
    void recordStage(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer = nullptr);
    void step();
    void runStage(Stage stage);

    // Bytes of GPU memory of the atlas, the brick table, the lists and the rebuild's buffers.
    uint64_t memoryBytes() const override;
    // As a scene runs it: recordRebuild by the rules (the bricks with a live cell, those the
    // emitters reach, and one brick of reach around them: the most a step's advection carries
    // smoke), timed as "rebuild_bricks", then the step.
    void recordSceneStep(VkCommandBuffer cmd, const SettleRules& rules,
                         gpu::GpuTimer* timer) override;
    StageDispatches lastScenePasses() const override;
    // The rebuild measures: nothing to record.
    uint32_t recordMeasureActivity(VkCommandBuffer, const gpu::Buffer&, gpu::GpuTimer*) override {
        return 0;
    }
    // The last rebuild's counts (finishRebuild); settled when no effect was live (`measured`)
    // and no brick is active or refused; with solids, which keep the bricks around the body
    // active and its air stirred, when no effect was live and no brick held live pigment.
    SolverActivity finishFrame(const gpu::Buffer& activity, bool measured, bool stepped,
                               const SettleRules& rules) override;
    // The sparse domain stands still over the stage.
    bool recordShift(VkCommandBuffer, glm::ivec3) override { return false; }
    PigmentVolume pigmentVolume() const override;
    std::vector<uint8_t> storedCells() const override { return activeCells(); }

    uint32_t passesPerStep() const { return uint32_t(stepOrder().size()) * options_.substeps; }

private:
    // The stage table (fluid/stage_table.h) names the stage functions below.
    friend std::span<const StageEntry> stageTable();

    using Writes = std::vector<gpu::DescriptorWrite>;

    SparseSmokeSolver(const gpu::Context& ctx, const SolverOptions& options, uint32_t maxBricks,
                      uint32_t initialSlots);
    // A stage's program; with the solids' tests compiled in while solids are set (constant 12).
    gpu::Program& program(const char* name, uint32_t target = 0, uint32_t variant = 0);
    void allocateAtlas(uint32_t slots); // keeps what the old atlas held
    void startGpuLayout();
    void recordActivation(VkCommandBuffer cmd); // the activated list's bricks start at rest // the
                                                // free stack from the table, for recordRebuild
    std::vector<uint32_t> slotTable() const;    // the brick table as the GPU has it
    void uploadList(gpu::Buffer& list, const std::vector<uint32_t>& bricks);
    void writeParameters();
    // The parameters, the brick table and a list of bricks at bindings 0-2.
    Writes common(const gpu::Buffer& list) const;
    void dispatch(VkCommandBuffer cmd, gpu::Program& program, const Writes& writes,
                  const gpu::Buffer& list);
    gpu::DescriptorWrite emitterWrite(uint32_t binding) const;
    void recordStageOnly(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer);

    void markSolids(VkCommandBuffer cmd);
    // The solids into their uniform buffer, in the command buffer (vkCmdUpdateBuffer).
    void recordSolidsUpload(VkCommandBuffer cmd);
    // The holders at binding 14 (or a stand-in without solids).
    gpu::DescriptorWrite solidWrite() const;
    void splatImpulses(VkCommandBuffer cmd);
    void advectVelocity(VkCommandBuffer cmd);
    void advectPigment(VkCommandBuffer cmd);
    void applyBuoyancy(VkCommandBuffer cmd);
    void applyBoundaries(VkCommandBuffer cmd);
    void computeDivergence(VkCommandBuffer cmd);
    void solvePressure(VkCommandBuffer cmd);
    void project(VkCommandBuffer cmd);

    const gpu::Context& ctx_;
    SolverOptions options_;
    SparseBricks layout_;
    std::map<std::tuple<std::string, uint32_t, uint32_t, bool>, gpu::Program> programs_;

    // The atlas: velocity[set][component], pigment[set] and pressure[set] ping-pong; current*
    // says which set is live (per component for velocity).
    uint32_t slots_ = 0;
    std::array<std::array<gpu::Buffer, 3>, 2> velocity_;
    std::array<gpu::Buffer, 2> pigment_;
    std::array<gpu::Buffer, 2> pressure_;
    gpu::Buffer divergence_;
    gpu::Buffer solidHolders_; // per stored cell (sparse_solids.glsl); made once solids come

    std::vector<shared::FluidSolid> solids_;
    gpu::Buffer solidsBuffer_; // kMaxGpuSolids of room (a uniform buffer); once solids come
    gpu::Buffer noSolids_;     // bound at binding 14 without solids
    std::array<int, 3> currentVelocity_{0, 0, 0};
    int currentPigment_ = 0;
    int currentPressure_ = 0;

    gpu::Buffer table_;         // slot per virtual brick
    gpu::Buffer active_;        // BrickListHeader + the active bricks
    gpu::Buffer activated_;     // BrickListHeader + the bricks activated by the last commit
    gpu::Buffer brickState_;    // per virtual brick: MFX_BRICK_WANTED, MFX_BRICK_FRESH
    gpu::Buffer wantedScratch_; // the rebuild's marks before and between the dilation's passes
    gpu::Buffer freeSlots_;     // the free stack: count, then slots
    gpu::Buffer refused_;       // the rebuild's refused bricks
    gpu::Buffer counters_;      // read back: refused, active, activated, free slots
    gpu::Buffer rebuildParameters_;
    bool gpuLayout_ = false; // recordRebuild has run: the GPU owns the table
    gpu::Buffer parameters_;
    gpu::Buffer ownEmitters_; // setEmitters' records
    VkBuffer emitterBuffer_ = VK_NULL_HANDLE;
    VkDeviceSize emitterBufferSize_ = 0;
    uint32_t emitterCount_ = 0;
    uint32_t dispatches_ = 0; // recorded so far (lastStepDispatches)
    StageDispatches lastStepDispatches_;
    uint32_t lastRebuildDispatches_ = 0;
    uint64_t sharedFaceMismatches_ = 0;
    uint32_t activeCount_ = 0; // active bricks as last counted (commit or rebuild)
};

} // namespace mfx::fluid
