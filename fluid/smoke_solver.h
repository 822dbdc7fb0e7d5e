// The smoke solver on the GPU: a 3D MAC grid in storage images, one compute shader per stage
// (shaders/<stage>.comp), the same stages and discretisation as the CPU reference
// (fluid/reference/), written down in docs/fluid.md. One sub-step:
//
//   splatImpulses → advectVelocity → advectPigment → applyBuoyancy → vorticityConfinement →
//   diffuseViscosity → applyBoundaries → computeDivergence → solvePressure → project →
//   applyBoundaries
//
// solvePressure runs Jacobi sweeps here (shaders/solve_pressure.comp), or red-black Gauss-Seidel,
// multigrid or MGPCG (fluid/gpu_multigrid.h), as SolverOptions::pressureSolver asks.
//
// Fields live in r32f / rgba32f 3D storage images in GENERAL layout. A stage that rewrites a whole
// field writes it into a storage buffer, which is then copied into the image (a CPU driver's image
// stores are costly; docs/fluid.md, "Grid"). Velocity and pigment are ping-ponged between image
// sets, and every dispatch or copy is separated by a memory barrier.
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/gpu/timer.h"
#include "fluid/gpu_multigrid.h"
#include "fluid/solver_options.h"

#include <array>
#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <tuple>
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
    const gpu::Image& pigmentImage() const { return pigment_[size_t(currentPigment_)]; }

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
    void recordShift(VkCommandBuffer cmd, glm::ivec3 cells);

    // Upper bound of timer passes one recordStep() makes.
    uint32_t passesPerStep() const { return uint32_t(kStepOrder.size()) * options_.substeps; }

private:
    SmokeSolver(const gpu::Context& ctx, const SolverOptions& options);
    void writeParameters();
    void recordStageOnly(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer);
    void barrier(VkCommandBuffer cmd) const;
    // Records, after the dispatches that wrote them, copies of whole fields written x-fastest
    // into buffers into their images, and the barrier that makes them visible to what follows.
    void copyToImages(VkCommandBuffer cmd,
                      std::initializer_list<std::pair<const gpu::Buffer*, gpu::Image*>> fields);
    void dispatch(VkCommandBuffer cmd, gpu::Program& program, VkDescriptorSet set,
                  glm::uvec3 extent, glm::uvec3 origin = glm::uvec3(0)) const;
    // Descriptor set of `program` for a combination of image-set indices `key`, made by
    // `writes()` the first time it is asked for.
    template <typename MakeWrites>
    VkDescriptorSet set(gpu::Program& program, std::tuple<int, int, int> key, MakeWrites writes);
    // Bindings firstBinding.. of the three components of velocity image set `set`.
    void addVelocity(std::vector<gpu::DescriptorWrite>& writes, int set,
                     uint32_t firstBinding) const;

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
    glm::uvec3 cells_;

    // velocity_[set][component]: sets 0 and 1 ping-pong (current_ says which is live), set 2 is
    // scratch for the viscosity sweeps.
    std::array<std::array<gpu::Image, 3>, 3> velocity_;
    std::array<gpu::Image, 2> pigment_;
    std::array<gpu::Image, 2> pressure_;
    gpu::Image divergence_;
    gpu::Image vorticity_;
    gpu::Image force_; // vorticity confinement force per cell (xyz)
    // Where stages that write a whole field write it before it is copied into the field's image
    // (shaders/fluid_common.glsl): one per velocity component, the first large enough for the
    // pigment.
    std::array<gpu::Buffer, 3> scratch_;
    // The pressure solve's working copies, four cells per vec4 (shaders/solve_pressure.comp):
    // pressure (ping-pong) and divergence; packedSolve_ is false for a grid too large for them.
    std::array<gpu::Buffer, 2> packedPressure_;
    gpu::Buffer packedDivergence_;
    bool packedSolve_ = true;
    std::unique_ptr<GpuMultigrid> multigrid_; // every pressure solver but Jacobi
    int currentVelocity_ = 0;
    int currentPigment_ = 0;
    int currentPressure_ = 0;

    gpu::Buffer parameters_;
    gpu::Buffer ownEmitters_;
    VkBuffer emitterBuffer_ = VK_NULL_HANDLE;
    VkDeviceSize emitterBufferSize_ = 0;
    uint32_t emitterCount_ = 0;
    // World-space bounds of the emitters when they came from the CPU (none for a GPU buffer).
    gpu::Buffer splatRegions_; // SplatRegion per target, written by emitter_bounds

    // The program of a stage (parts 1 and 2: the second and third programs of vorticity
    // confinement) for one target field (MFX_TARGET_*, a specialization constant), compiled on
    // first use.
    gpu::Program& program(Stage stage, int part = 0, uint32_t target = 0);
    std::map<std::tuple<int, int, uint32_t>, gpu::Program> programs_; // node addresses are stable
    std::map<std::tuple<const gpu::Program*, int, int, int>, VkDescriptorSet> sets_;
    gpu::Program activityProgram_;
    // fp16 storage: the programs storing a buffer into an r16f / rgba16f image, and their sets.
    std::array<gpu::Program, 2> storeHalf_;
    std::map<std::pair<VkBuffer, VkImage>, VkDescriptorSet> storeHalfSets_;
    std::map<std::tuple<int, int, VkBuffer>, VkDescriptorSet> activitySets_;
    mutable uint32_t dispatches_ = 0; // vkCmdDispatch calls recorded so far
    std::vector<std::pair<std::string, uint32_t>> lastStepDispatches_;
};

} // namespace mfx::fluid
