// The smoke solver on the GPU: a 3D MAC grid in storage images, one compute shader per stage
// (shaders/fluid/<stage>.comp), the same stages and discretisation as the CPU reference
// (fluid/reference/), written down in docs/fluid.md. One sub-step:
//
//   splatImpulses → advectVelocity → advectPigment → applyBuoyancy → vorticityConfinement →
//   diffuseViscosity → applyBoundaries → computeDivergence → solvePressure → project →
//   applyBoundaries
//
// solvePressure runs Jacobi sweeps here (shaders/fluid/solve_pressure.comp), or red-black
// Gauss-Seidel, multigrid or MGPCG (fluid/gpu_multigrid.h), as SolverOptions::pressureSolver asks.
//
// The fields are a SmokeFields (fluid/smoke_fields.h): r32f / rgba32f 3D storage images in GENERAL
// layout. A stage that rewrites a whole field writes it into a storage buffer, which is then
// copied into the image (a CPU driver's image stores are costly; docs/fluid.md, "Grid"). Velocity
// and pigment are ping-ponged between image sets, and every dispatch or copy is separated by a
// memory barrier. The stages' programs come from one table (fluid/stage_programs.h); each stage
// below binds its resources as it records (core/gpu/program.h).
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/gpu/timer.h"
#include "fluid/gpu_multigrid.h"
#include "fluid/smoke_fields.h"
#include "fluid/solver_options.h"
#include "fluid/stage_programs.h"

#include <array>
#include <initializer_list>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace mfx::gpu {
class Context;
}

namespace mfx::fluid {

class SmokeSolver {
public:
    // Fails when the options are invalid or the grid exceeds the device's 3D image size.
    static Result<std::unique_ptr<SmokeSolver>> create(const gpu::Context& ctx,
                                                       const SolverOptions& options);
    SmokeSolver(const SmokeSolver&) = delete;
    SmokeSolver& operator=(const SmokeSolver&) = delete;

    const SolverOptions& options() const { return options_; }
    // The current pigment field (rgba32f, GENERAL layout, sampled usage): what a renderer draws.
    const gpu::Image& pigmentImage() const {
        return fields_.pigment[size_t(fields_.currentPigment)];
    }

    // Uploads / reads back every field (waits for the GPU).
    void setState(const FieldState& state);
    FieldState state();

    // Emitters for the following steps, copied into the solver's own buffer after validation.
    Status setEmitters(std::span<const shared::FluidEmitter> emitters);
    // Emitters read from a GPU buffer filled by other GPU work (e.g. trajectory segments):
    // `count` records of shared::FluidEmitter. Not checked on the CPU; the splat shader ignores
    // records with a non-finite position, radius or strength.
    void setEmitterBuffer(const gpu::Buffer& buffer, uint32_t count);

    // Records one whole step (all sub-steps) into `cmd`. With a timer, each stage is a pass
    // named after it (stageName()), once per sub-step. The parameters uniform is written now,
    // so the previous recording must have finished executing.
    void recordStep(VkCommandBuffer cmd, gpu::GpuTimer* timer = nullptr);
    // Records one stage alone (with the sub-step dt).
    void recordStage(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer = nullptr);

    // Convenience: record, submit and wait.
    void step();
    void runStage(Stage stage);

    // The compute dispatches of each stage in the last recordStep(), in step order (a stage that
    // runs twice, apply_boundaries, is summed), and GPU memory of the fields and buffers.
    const std::vector<std::pair<std::string, uint32_t>>& lastStepDispatches() const {
        return lastStepDispatches_;
    }
    uint64_t memoryBytes() const;
    // Sweeps, V-cycles or CG iterations of the last pressure solve (MGPCG stops early on its
    // tolerance: read back from the GPU, so the step must have finished).
    uint32_t lastPressureIterations() const;

    // Records measure_activity: the largest pigment alpha and the largest cell-centre speed of
    // the current fields into `out` (two floats as uint bits, cleared first), for deciding whether
    // the smoke has settled. `out` needs STORAGE_BUFFER and TRANSFER_DST usage.
    void recordMeasureActivity(VkCommandBuffer cmd, const gpu::Buffer& out);

    // Records a move of the grid by whole cells: afterwards field(q) holds what field(q + cells)
    // held (velocity, pigment and pressure), and what comes in from outside is 0. For a grid that
    // follows a character: the smoke stays where it was in the world.
    void recordShift(VkCommandBuffer cmd, glm::ivec3 cells) { fields_.recordShift(cmd, cells); }

    // Upper bound of timer passes one recordStep() makes.
    uint32_t passesPerStep() const { return uint32_t(kStepOrder.size()) * options_.substeps; }

private:
    using Writes = std::vector<gpu::DescriptorWrite>;

    SmokeSolver(const gpu::Context& ctx, const SolverOptions& options);
    void writeParameters();
    void recordStageOnly(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer);
    // Records, after the dispatches that wrote them, copies of whole fields written x-fastest
    // into buffers into their images, and the barrier that makes them visible to what follows.
    void copyToImages(VkCommandBuffer cmd,
                      std::initializer_list<std::pair<const gpu::Buffer*, gpu::Image*>> fields);
    // Binds `program` with `writes` and dispatches it over `extent` items.
    void dispatch(VkCommandBuffer cmd, gpu::Program& program,
                  std::span<const gpu::DescriptorWrite> writes, glm::uvec3 extent) const;
    // The parameters uniform at binding 0, then the three components of velocity image set `set`
    // at bindings 1-3 (the layout of most stages).
    Writes withVelocity(int set) const;

    void splatImpulses(VkCommandBuffer cmd);
    std::vector<uint32_t> advectionPasses() const;
    void advectVelocity(VkCommandBuffer cmd);
    void advectPigment(VkCommandBuffer cmd);
    void applyBuoyancy(VkCommandBuffer cmd);
    void vorticityConfinement(VkCommandBuffer cmd);
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

    gpu::Buffer parameters_;
    gpu::Buffer ownEmitters_;
    VkBuffer emitterBuffer_ = VK_NULL_HANDLE;
    VkDeviceSize emitterBufferSize_ = 0;
    uint32_t emitterCount_ = 0;
    gpu::Buffer splatRegions_; // SplatRegion per target, written by emitter_bounds

    mutable uint32_t dispatches_ = 0; // vkCmdDispatch calls recorded so far
    std::vector<std::pair<std::string, uint32_t>> lastStepDispatches_;
};

} // namespace mfx::fluid
