// The pressure solvers of SolverOptions beyond Jacobi, on the GPU: red-black Gauss-Seidel,
// multigrid V-cycles and MGPCG (docs/fluid.md, "Accuracy options"), computing what the CPU
// reference computes (fluid/reference/red_black_gauss_seidel.cpp, multigrid.cpp, mgpcg.cpp): the
// same hierarchy and finite-volume operators, sweep rule and colour order, transfers, coarsest
// solve and V-cycle variants, in fp32. SmokeSolver::solvePressure records one of these instead of
// its Jacobi sweeps.
//
// Every level's vectors live in one storage buffer, four x-consecutive cells per vec4
// (shaders/shared/pressure_solve.h), as the Jacobi sweeps keep pressure between sweeps: on
// lavapipe those run 1.36 times faster on such buffers than on r32f images (docs/fluid.md). The
// levels' stencils, transfers and the coarsest level's exact solution operator are tables made
// once on the CPU from the reference's own hierarchy (Multigrid in
// fluid/reference/pressure_equation.h), so both sides agree on them by construction. One shader
// per kernel, named as the Kernel enumerators below.
//
// MGPCG stops on its tolerance without reading anything back: the step is recorded with
// cgMaxIterations iterations, each of whose dispatches is indirect, and the kernel that finds the
// tolerance met (finish_reduction) sets every indirect dispatch to zero workgroups. The iterations
// after that cost their empty dispatches and barriers only, not their work.
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/result.h"
#include "fluid/solver_options.h"
#include "shaders/shared/pressure_solve.h"

#include <array>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

namespace mfx::gpu {
class Context;
}

namespace mfx::fluid {

// MultigridOptions::brick on `ctx`'s device: `requested`, or with 0 the device's choice.
uint32_t multigridBrick(uint32_t requested, const gpu::Context& ctx);
// MultigridOptions::coarseCells resolved: `requested`, or with 0 the default, 4,096 (16³).
uint32_t coarseCycleCells(uint32_t requested);
// MultigridOptions::coarseGroup on `ctx`'s device for bricks of `brick` rows and layers and a
// fused part of levels of at most `coarseCells` cells: `requested`, or with 0 the device's choice.
uint32_t coarseCycleGroup(uint32_t requested, uint32_t brick, uint32_t coarseCells,
                          const gpu::Context& ctx);
// Whether `options`' V-cycle restricts with the residual computed in the restriction
// (MultigridOptions::residualInRestriction on `ctx`'s device; the multigrid solver only).
bool residualInRestriction(const SolverOptions& options, const gpu::Context& ctx);

class GpuMultigrid {
public:
    // The largest coarsest level solved exactly (a dense n x n operator, applied by the eight
    // invocations of cycle_coarse_levels: n^2 / 32 loop iterations each, which must stay well
    // within the 65535 a CPU driver, llvmpipe, allows an invocation in all). Every hierarchy
    // built down to 2 cells per axis ends far below it; only a small multigrid.levels can exceed
    // it.
    static constexpr uint32_t kMaxCoarsestCells = 512;

    // For options.pressureSolver RedBlackGaussSeidel, Multigrid or MultigridPcg. Fails when the
    // coarsest level would exceed kMaxCoarsestCells or the vectors exceed one storage buffer.
    static Result<std::unique_ptr<GpuMultigrid>> create(const gpu::Context& ctx,
                                                        const SolverOptions& options);
    GpuMultigrid(const GpuMultigrid&) = delete;
    GpuMultigrid& operator=(const GpuMultigrid&) = delete;

    // Records the whole pressure solve: b = -h² div from `divergence`, the start from `pressure`
    // (warm start) or 0, the solution written one float per cell, x-fastest, into `out` (the
    // caller copies it into the pressure image). With `solids`, `solidFlags` holds the solid flag
    // bytes (shaders/fluid/fluid_solids.glsl) that level 0's stencils read: a solid cell has no
    // unknown and stays 0, a solid neighbour is not counted (fluid/reference/pressure_equation.h);
    // without, it is bound but not read (any storage buffer). Every dispatch is followed by a
    // barrier. Returns the number of dispatches recorded.
    uint32_t record(VkCommandBuffer cmd, const gpu::Image& divergence, const gpu::Image& pressure,
                    const gpu::Buffer& out, const gpu::Buffer& solidFlags, bool solids);

    // Sweeps, V-cycles or CG iterations of the last solve; for MGPCG read back from the GPU (the
    // solve must have finished).
    uint32_t lastIterations() const;
    size_t levelCount() const { return levels_.size(); }
    // Invocations of the workgroup that cycles the coarse levels (MultigridOptions::coarseGroup,
    // resolved for this device).
    uint32_t coarseGroup() const;
    // Rows (y) and layers (z) of a brick, the elements one invocation handles
    // (MultigridOptions::brick resolved for this device; shaders/fluid/pressure_solve_common.glsl,
    // levelBrick).
    uint32_t brick() const { return brick_; }
    uint64_t memoryBytes() const;

private:
    enum Kernel {
        LoadPressureSystem,
        StorePressure,
        RelaxColour,
        ComputeResidual,
        RestrictResidual,
        ProlongCorrection,
        CycleCoarseLevels,
        RemoveMean,
        ApplyPressureOperator,
        UpdateCgSolution,
        SumCgProducts,
        UpdateCgDirection,
        FinishReduction,
        KernelCount,
    };
    // Where a kernel runs: one invocation per brick of a level, or one workgroup.
    enum class Grid { Level, Single };
    struct Level {
        glm::ivec3 cells{1};
        int rowLength = 1;    // vec4 elements per row
        int elements = 1;     // vec4 elements of one vector
        std::array<int, 2> x; // the solution or correction, ping-ponged by relax_colour
        int current = 0;      // which of x is live
        int b = 0;            // right-hand side
        int r = 0;            // residual
    };

    GpuMultigrid(const gpu::Context& ctx, const SolverOptions& options);

    void solveRedBlack(VkCommandBuffer cmd);
    void solveMultigrid(VkCommandBuffer cmd);
    void solveMgpcg(VkCommandBuffer cmd);

    // One V-cycle on level l for A x = b (b at `rhs`), improving level l's live x in place
    // (fluid/reference/multigrid.cpp, Multigrid::cycle). `startFromZero`: x is 0 on entry (not
    // read). `symmetric`: the MGPCG preconditioner's cycle (P^T, black-red post-smoothing).
    void vCycle(VkCommandBuffer cmd, size_t l, int rhs, uint32_t preSmooth, uint32_t postSmooth,
                bool symmetric, bool startFromZero, bool indirect);
    // `sweeps` red-black sweeps of level l's x (black-red with `blackFirst`).
    void relax(VkCommandBuffer cmd, size_t l, int rhs, uint32_t sweeps, bool blackFirst,
               bool startFromZero, bool indirect);
    void finish(VkCommandBuffer cmd, uint32_t step, uint32_t slot, uint32_t flags, bool indirect);
    // load_pressure_system into level 0's b and `x`; b made mean-free when singular, with the
    // partial sums of (b, b) when `sumsFlags` asks for them.
    void loadSystem(VkCommandBuffer cmd, int x, uint32_t sumsFlags);

    shared::PressureDispatch push(int level) const;
    // Level l's bricks (shaders/fluid/pressure_solve_common.glsl), and the workgroups of a dispatch
    // over them.
    glm::uvec3 levelBricks(size_t l) const;
    glm::uvec3 levelGroups(size_t l) const;
    // Records one dispatch and a barrier; Grid::Level runs on level `gridLevel` (default: the
    // constants' level), indirect from the level's entry of arguments_ when `indirect`.
    void run(VkCommandBuffer cmd, Kernel kernel, const shared::PressureDispatch& constants,
             Grid grid, bool indirect, int gridLevel = -1);
    gpu::Program& program(Kernel kernel);
    void barrier(VkCommandBuffer cmd) const;

    const gpu::Context& ctx_;
    SolverOptions options_;
    bool singular_ = false;
    uint32_t brick_ = 4;
    std::vector<Level> levels_;
    // The first level whose V-cycle runs in one workgroup (cycle_coarse_levels): from it on every
    // level has at most kFusedBricks bricks (gpu_multigrid.cpp).
    size_t fusedLevel_ = 0;
    // Coarse indices a prolongation brick reads along an axis, and fine indices a P^T
    // restriction brick reads along x and along y or z (specialization constants of
    // shaders/fluid/pressure_multigrid.glsl, from the tables).
    int prolongSlots_ = 1;
    int restrictSlotsX_ = 1;
    int restrictSlotsYZ_ = 1;
    // Level 0's conjugate gradient vectors (MGPCG): pressure, residual, direction, A direction.
    int cgPressure_ = 0, cgResidual_ = 0, cgDirection_ = 0, cgProduct_ = 0;
    glm::uvec3 partialGroups_{1}; // workgroups of a level-0 dispatch
    uint32_t partialsPerSlot_ = 1;

    gpu::Buffer levelTable_;
    gpu::Buffer axisCells_;
    gpu::Buffer restrictions_;
    gpu::Buffer coarsestMatrix_;
    gpu::Buffer vectors_;
    gpu::Buffer partials_;
    gpu::Buffer scalars_;
    gpu::Buffer arguments_;         // indirect dispatches of the CG loop: one per level and one
    gpu::Buffer argumentsTemplate_; // workgroup; copied in at each solve

    // Per kernel, without and with solids (specialization constant 15, kSolids).
    std::array<std::array<gpu::Program, KernelCount>, 2> programs_;
    bool solids_ = false; // this record()'s
    const gpu::Buffer* solidFlags_ = nullptr;
    const gpu::Image* divergence_ = nullptr;
    const gpu::Image* pressure_ = nullptr;
    const gpu::Buffer* out_ = nullptr;
    uint32_t dispatches_ = 0;
    bool resourcesPushed_ = false; // by this record()'s first dispatch
};

} // namespace mfx::fluid
