// Red-black Gauss-Seidel, multigrid V-cycles and MGPCG on the GPU (gpu_multigrid.h). The
// algorithms are the reference's (fluid/reference/red_black_gauss_seidel.cpp, multigrid.cpp,
// mgpcg.cpp; Trottenberg, Oosterlee, Schueller, "Multigrid", 2001, ch. 2; McAdams, Sifakis,
// Teran, "A Parallel Multigrid Poisson Solver for Fluids Simulation on Large Grids", SCA 2010;
// Saad, "Iterative Methods for Sparse Linear Systems", 2003, alg. 9.1), recorded as dispatches of
// the kernels in
// shaders/fluid/{load_pressure_system,relax_colour,compute_residual,restrict_residual,
// prolong_correction,cycle_coarse_levels,remove_mean,apply_pressure_operator,update_cg_solution,
// sum_cg_products,update_cg_direction,finish_reduction,store_pressure}.comp.
#include "fluid/gpu_multigrid.h"

#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "fluid/reference/pressure_equation.h"
#include "shaders/embedded.h"

#include <algorithm>
#include <cstring>

namespace mfx::fluid {

namespace {

// Partial-sum slots (shaders/fluid/pressure_partial_sums.glsl); finish_reduction reads a slot and
// the next one.
constexpr uint32_t kSlotRhsSum = 0;           // sum b (its mean)
constexpr uint32_t kSlotRhsSquares = 1;       // (b, b)
constexpr uint32_t kSlotResidualSquares = 2;  // (r, r), CG's first residual
constexpr uint32_t kSlotResidualSum = 3;      // sum r (its mean)
constexpr uint32_t kSlotDirectionProduct = 4; // (d, A d)
constexpr uint32_t kSlotCheck = 5;            // (r, r) after an update
constexpr uint32_t kSlotPreconditioned = 6;   // (r, z), sum z, sum r

// The coarse levels' V-cycle (cycle_coarse_levels.comp) runs in one workgroup of
// coarseGroup() invocations on the levels of 16^3 cells and below. On a CPU driver 8: one SIMD
// row, where a barrier costs the more, the more invocations wait at it; measured on lavapipe at
// 64^3, levels 16^3 to 2^3 as separate dispatches cost 2.4 ms per V-cycle, in one dispatch of
// 256 invocations 2.6 ms, of 8 invocations 0.8 ms. On a GPU one invocation per brick of the first
// level it takes (64 bricks of 4 rows and layers, 1024 of one): there a phase costs its loads'
// latency, which fewer invocations would pay several times in a row (on an H200 with bricks of 4,
// 8 invocations made the 128^3 multigrid solve 5.9 ms against 4.1 ms with 64).
constexpr uint32_t kCpuCoarseGroup = 8;
constexpr uint32_t kCpuBrick = 4;
constexpr uint32_t kGpuBrick = 1;

} // namespace

uint32_t multigridBrick(uint32_t requested, const gpu::Context& ctx) {
    if (requested != 0) return requested;
    return ctx.info().isCpu() ? kCpuBrick : kGpuBrick;
}

uint32_t coarseCycleCells(uint32_t requested) {
    return requested != 0 ? requested : 16 * 16 * 16;
}

uint32_t coarseCycleGroup(uint32_t requested, uint32_t brick, uint32_t coarseCells,
                          const gpu::Context& ctx) {
    if (requested != 0) return requested;
    if (ctx.info().isCpu()) return kCpuCoarseGroup;
    // One invocation per brick (4 cells by brick rows by brick layers) of the largest fused level.
    const uint32_t bricks = std::max(coarseCycleCells(coarseCells) / (4 * brick * brick), 1u);
    return std::min({bricks, ctx.limits().maxComputeWorkGroupInvocations,
                     ctx.limits().maxComputeWorkGroupSize[0]});
}

bool residualInRestriction(const SolverOptions& options, const gpu::Context& ctx) {
    if (options.pressureSolver != PressureSolver::Multigrid) return false;
    const ByDevice choice = options.multigrid.residualInRestriction;
    return choice == ByDevice::On || (choice == ByDevice::Auto && !ctx.info().isCpu());
}

// --- Programs and dispatches ---------------------------------------------------------------------

gpu::Program& GpuMultigrid::program(Kernel kernel) {
    gpu::Program& slot = programs_[solids_ ? 1 : 0][size_t(kernel)];
    if (slot.pipeline() != VK_NULL_HANDLE) return slot;
    using namespace mfx::shaders;
    struct Source {
        const char* name;
        std::span<const uint32_t> spirv;
    };
    const Source sources[KernelCount] = {
        {"load_pressure_system", options_.storage == Storage::Float16
                                     ? load_pressure_system_comp_half
                                     : load_pressure_system_comp},
        {"store_pressure", store_pressure_comp},
        {"relax_colour", relax_colour_comp},
        {"compute_residual", compute_residual_comp},
        {"restrict_residual", restrict_residual_comp},
        {"prolong_correction", prolong_correction_comp},
        {"cycle_coarse_levels", cycle_coarse_levels_comp},
        {"remove_mean", remove_mean_comp},
        {"apply_pressure_operator", apply_pressure_operator_comp},
        {"update_cg_solution", update_cg_solution_comp},
        {"sum_cg_products", sum_cg_products_comp},
        {"update_cg_direction", update_cg_direction_comp},
        {"finish_reduction", finish_reduction_comp},
    };
    gpu::ComputeProgramDesc desc;
    desc.name = sources[kernel].name;
    desc.spirv = sources[kernel].spirv;
    desc.pushConstantSize = sizeof(shared::PressureDispatch);
    // Ids 0-2: the workgroup shape; 3-4: a brick's rows and layers; 5-7: the transfers' slots;
    // 8: the V-cycle's kind (MGPCG's symmetric one, or the multigrid solver's); 9: the residual
    // computed by the restriction; 15: solids (kSolids, level 0's stencils read their flags).
    const bool fused = kernel == CycleCoarseLevels;
    desc.specialization = {fused ? coarseGroup() : options_.workgroup[0],
                           fused ? 1u : options_.workgroup[1],
                           fused ? 1u : options_.workgroup[2],
                           brick_,
                           brick_,
                           uint32_t(prolongSlots_),
                           uint32_t(restrictSlotsX_),
                           uint32_t(restrictSlotsYZ_),
                           options_.pressureSolver == PressureSolver::MultigridPcg ? 1u : 0u,
                           residualInRestriction(options_, ctx_) ? 1u : 0u};
    desc.specialization.resize(15, 0u); // ids 10-14: none
    desc.specialization.push_back(solids_ ? 1u : 0u);
    slot = gpu::createComputeProgram(ctx_, desc);
    return slot;
}

uint32_t GpuMultigrid::coarseGroup() const {
    return coarseCycleGroup(options_.multigrid.coarseGroup, brick_, options_.multigrid.coarseCells,
                            ctx_);
}

void GpuMultigrid::barrier(VkCommandBuffer cmd) const {
    const VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                                         VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT |
                                         VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    gpu::memoryBarrier(
        cmd, stages, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, stages,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
            VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT |
            VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

glm::uvec3 GpuMultigrid::levelBricks(size_t l) const {
    const Level& level = levels_[l];
    return {uint32_t(level.rowLength), gpu::groupCount(uint32_t(level.cells.y), brick_),
            gpu::groupCount(uint32_t(level.cells.z), brick_)};
}

glm::uvec3 GpuMultigrid::levelGroups(size_t l) const {
    const glm::uvec3 bricks = levelBricks(l);
    const std::array<uint32_t, 3>& group = options_.workgroup;
    return {gpu::groupCount(bricks.x, group[0]), gpu::groupCount(bricks.y, group[1]),
            gpu::groupCount(bricks.z, group[2])};
}

shared::PressureDispatch GpuMultigrid::push(int level) const {
    shared::PressureDispatch p{};
    p.level = level;
    p.partials = partialsPerSlot_;
    p.scale = options_.cgTolerance;
    p.limit = uint32_t(levels_.size() + 1);
    return p;
}

void GpuMultigrid::run(VkCommandBuffer cmd, Kernel kernel,
                       const shared::PressureDispatch& constants, Grid grid, bool indirect,
                       int gridLevel) {
    gpu::Program& prog = program(kernel);
    // Every kernel binds the same resources (shaders/fluid/pressure_solve_common.glsl) with the
    // same push constants, so their layouts are compatible: the resources are pushed with the
    // solve's first dispatch and stay bound for the rest (a solve of many small dispatches would
    // otherwise spend its time pushing them again).
    if (resourcesPushed_) {
        prog.bindPipeline(cmd);
    } else {
        const gpu::DescriptorWrite writes[] = {
            gpu::bindBuffer(0, levelTable_),
            gpu::bindBuffer(1, axisCells_),
            gpu::bindBuffer(2, restrictions_),
            gpu::bindBuffer(3, coarsestMatrix_),
            gpu::bindBuffer(4, vectors_),
            gpu::bindBuffer(5, vectors_),
            gpu::bindBuffer(6, partials_),
            gpu::bindBuffer(7, scalars_),
            gpu::bindBuffer(8, arguments_),
            gpu::bindImage(9, *divergence_, VK_IMAGE_LAYOUT_GENERAL),
            gpu::bindImage(10, *pressure_, VK_IMAGE_LAYOUT_GENERAL),
            gpu::bindBuffer(11, *out_),
            gpu::bindBuffer(15, *solidFlags_),
        };
        prog.bind(cmd, writes);
        resourcesPushed_ = true;
    }
    prog.push(cmd, constants);
    ++dispatches_;
    const size_t levelCount = levels_.size();
    size_t entry = 0;
    glm::uvec3 groups(1);
    switch (grid) {
    case Grid::Level:
        entry = size_t(gridLevel >= 0 ? gridLevel : constants.level);
        groups = levelGroups(entry);
        break;
    case Grid::Single:
        entry = levelCount;
        break;
    }
    if (indirect)
        vkCmdDispatchIndirect(cmd, arguments_.get(), entry * sizeof(glm::uvec4));
    else
        vkCmdDispatch(cmd, groups.x, groups.y, groups.z);
    barrier(cmd);
}

void GpuMultigrid::finish(VkCommandBuffer cmd, uint32_t step, uint32_t slot, uint32_t flags,
                          bool indirect) {
    shared::PressureDispatch p = push(0);
    p.step = step;
    p.slot = slot;
    p.flags = flags | (singular_ ? MFX_PRESSURE_SINGULAR : 0u);
    run(cmd, FinishReduction, p, Grid::Single, indirect);
}

// --- Recording
// ------------------------------------------------------------------------------------

uint32_t GpuMultigrid::record(VkCommandBuffer cmd, const gpu::Image& divergence,
                              const gpu::Image& pressure, const gpu::Buffer& out,
                              const gpu::Buffer& solidFlags, bool solids) {
    if (solids && options_.pressureSolver != PressureSolver::RedBlackGaussSeidel &&
        levels_.size() < 2)
        throw std::logic_error("multigrid: solids need a coarse level (validateSolidOptions)");
    solids_ = solids;
    solidFlags_ = &solidFlags;
    divergence_ = &divergence;
    pressure_ = &pressure;
    out_ = &out;
    dispatches_ = 0;
    resourcesPushed_ = false; // another program may have pushed its own since the last solve
    switch (options_.pressureSolver) {
    case PressureSolver::RedBlackGaussSeidel:
        solveRedBlack(cmd);
        break;
    case PressureSolver::Multigrid:
        solveMultigrid(cmd);
        break;
    case PressureSolver::MultigridPcg:
        solveMgpcg(cmd);
        break;
    case PressureSolver::Jacobi:
        break;
    }
    return dispatches_;
}

void GpuMultigrid::relax(VkCommandBuffer cmd, size_t l, int rhs, uint32_t sweeps, bool blackFirst,
                         bool startFromZero, bool indirect) {
    Level& level = levels_[l];
    for (uint32_t half = 0; half < 2 * sweeps; ++half) {
        shared::PressureDispatch p = push(int(l));
        p.source = level.x[size_t(level.current)];
        p.result = level.x[size_t(1 - level.current)];
        p.rhs = rhs;
        p.step = (half % 2 == 0) == blackFirst ? 1u : 0u;
        p.flags = startFromZero && half == 0 ? MFX_PRESSURE_ZERO_INPUT : 0u;
        run(cmd, RelaxColour, p, Grid::Level, indirect);
        level.current = 1 - level.current;
    }
}

void GpuMultigrid::vCycle(VkCommandBuffer cmd, size_t l, int rhs, uint32_t preSmooth,
                          uint32_t postSmooth, bool symmetric, bool startFromZero, bool indirect) {
    Level& level = levels_[l];
    if (l == fusedLevel_) {
        // This level and the coarser ones in one workgroup, which starts and ends with each
        // level's live x its first.
        if (level.current != 0) throw std::logic_error("multigrid: a level's live x is its second");
        shared::PressureDispatch p = push(int(l));
        p.rhs = rhs;
        p.flags = startFromZero ? MFX_PRESSURE_ZERO_INPUT : 0u;
        p.limit = uint32_t(levels_.size());
        p.preSmooth = preSmooth;
        p.postSmooth = postSmooth;
        run(cmd, CycleCoarseLevels, p, Grid::Single, indirect);
        return;
    }
    Level& coarse = levels_[l + 1];
    relax(cmd, l, rhs, preSmooth, false, startFromZero, indirect);

    // On the coarse level's elements; the coarse correction starts at 0. The restriction restricts
    // the residual vector, or computes the residual of x as it goes (residualInRestriction).
    shared::PressureDispatch restriction = push(int(l));
    restriction.source = level.x[size_t(level.current)];
    restriction.rhs = rhs;
    if (!residualInRestriction(options_, ctx_)) {
        shared::PressureDispatch residual = push(int(l));
        residual.source = level.x[size_t(level.current)];
        residual.rhs = rhs;
        residual.result = level.r;
        run(cmd, ComputeResidual, residual, Grid::Level, indirect);
        restriction.source = level.r;
    }
    restriction.result = coarse.b;
    restriction.other = coarse.x[size_t(coarse.current)];
    run(cmd, RestrictResidual, restriction, Grid::Level, indirect, int(l + 1));

    vCycle(cmd, l + 1, coarse.b, preSmooth, postSmooth, symmetric, false, indirect);

    shared::PressureDispatch prolong = push(int(l));
    prolong.source = coarse.x[size_t(coarse.current)];
    prolong.result = level.x[size_t(level.current)];
    run(cmd, ProlongCorrection, prolong, Grid::Level, indirect);
    relax(cmd, l, rhs, postSmooth, symmetric, false, indirect);
}

// jacobiIterations sweeps on b = -h² div as the Jacobi sweep takes it (not made mean-free), from
// 0 or the last pressure (red_black_gauss_seidel.cpp).
void GpuMultigrid::solveRedBlack(VkCommandBuffer cmd) {
    Level& level = levels_[0];
    level.current = 0;
    shared::PressureDispatch load = push(0);
    load.result = level.x[0];
    load.rhs = level.b;
    load.scale = -options_.grid.cellSize * options_.grid.cellSize;
    load.flags = options_.warmStart ? MFX_PRESSURE_WARM_START : 0u;
    run(cmd, LoadPressureSystem, load, Grid::Level, false);
    relax(cmd, 0, level.b, options_.jacobiIterations, false, false, false);
    shared::PressureDispatch store = push(0);
    store.source = level.x[size_t(level.current)];
    run(cmd, StorePressure, store, Grid::Level, false);
}

// Loads b (made mean-free when singular) into level 0's b and the start into `x`.
void GpuMultigrid::loadSystem(VkCommandBuffer cmd, int x, uint32_t sumsFlags) {
    const Level& level = levels_[0];
    shared::PressureDispatch load = push(0);
    load.result = x;
    load.rhs = level.b;
    load.scale = -options_.grid.cellSize * options_.grid.cellSize;
    load.slot = kSlotRhsSum;
    load.flags = (options_.warmStart ? MFX_PRESSURE_WARM_START : 0u) |
                 (singular_ ? MFX_PRESSURE_PARTIAL_SUMS : 0u);
    run(cmd, LoadPressureSystem, load, Grid::Level, false);
    // The mean of b, over the cells load_pressure_system counted (the fluid ones, with solids),
    // which the later means are over too.
    if (singular_) finish(cmd, MFX_REDUCE_MEAN, kSlotRhsSum, MFX_PRESSURE_COUNT_CELLS, false);
    if (singular_ || sumsFlags != 0) {
        shared::PressureDispatch center = push(0);
        center.result = level.b;
        center.slot = kSlotRhsSquares;
        center.flags = (singular_ ? MFX_PRESSURE_SUBTRACT_MEAN : 0u) | sumsFlags;
        run(cmd, RemoveMean, center, Grid::Level, false);
    }
}

// multigrid.cycles V-cycles on the mean-free b, from 0 or the last pressure (multigrid.cpp).
void GpuMultigrid::solveMultigrid(VkCommandBuffer cmd) {
    Level& level = levels_[0];
    level.current = 0;
    loadSystem(cmd, level.x[0], 0);
    for (uint32_t cycle = 0; cycle < options_.multigrid.cycles; ++cycle)
        vCycle(cmd, 0, level.b, options_.multigrid.preSmooth, options_.multigrid.postSmooth, false,
               false, false);
    shared::PressureDispatch store = push(0);
    store.source = level.x[size_t(level.current)];
    run(cmd, StorePressure, store, Grid::Level, false);
}

// Preconditioned conjugate gradient (mgpcg.cpp; Saad 2003, alg. 9.1) with one symmetric V-cycle
// from 0 as M. Everything after the first residual is dispatched indirectly, so that once
// finish_reduction finds the tolerance met the rest of the recorded iterations do nothing.
void GpuMultigrid::solveMgpcg(VkCommandBuffer cmd) {
    const Level& level0 = levels_[0];
    const uint32_t smooth =
        std::max({options_.multigrid.preSmooth, options_.multigrid.postSmooth, 1u});
    VkBufferCopy copy{0, 0, arguments_.size};
    vkCmdCopyBuffer(cmd, argumentsTemplate_.get(), arguments_.get(), 1, &copy);
    barrier(cmd);

    // b (mean-free when singular) and (b, b); r = b - A p (mean-free) and (r, r).
    loadSystem(cmd, cgPressure_, MFX_PRESSURE_PARTIAL_SUMS);
    shared::PressureDispatch residual = push(0);
    residual.source = cgPressure_;
    residual.rhs = level0.b;
    residual.result = cgResidual_;
    residual.slot = kSlotResidualSum;
    residual.flags = singular_ ? MFX_PRESSURE_PARTIAL_SUMS : 0u;
    run(cmd, ComputeResidual, residual, Grid::Level, false);
    if (singular_) finish(cmd, MFX_REDUCE_MEAN, kSlotResidualSum, 0, false);
    shared::PressureDispatch center = push(0);
    center.result = cgResidual_;
    center.slot = kSlotResidualSquares;
    center.flags = (singular_ ? MFX_PRESSURE_SUBTRACT_MEAN : 0u) | MFX_PRESSURE_PARTIAL_SUMS;
    run(cmd, RemoveMean, center, Grid::Level, false);
    finish(cmd, MFX_REDUCE_CG_START, kSlotRhsSquares, 0, false);

    // z = M r, its mean removed in (r, z) and d; d = z.
    auto precondition = [&](bool first) {
        vCycle(cmd, 0, cgResidual_, smooth, smooth, true, true, true);
        shared::PressureDispatch sums = push(0);
        sums.source = levels_[0].x[size_t(levels_[0].current)];
        sums.rhs = cgResidual_;
        sums.slot = kSlotPreconditioned;
        run(cmd, SumCgProducts, sums, Grid::Level, true);
        finish(cmd, MFX_REDUCE_CG_BETA, kSlotPreconditioned, first ? MFX_PRESSURE_FIRST : 0u, true);
        shared::PressureDispatch direction = push(0);
        direction.source = sums.source;
        direction.result = cgDirection_;
        direction.flags = first ? MFX_PRESSURE_FIRST : 0u;
        run(cmd, UpdateCgDirection, direction, Grid::Level, true);
    };
    precondition(true);
    for (uint32_t iteration = 0; iteration < options_.cgMaxIterations; ++iteration) {
        shared::PressureDispatch apply = push(0);
        apply.source = cgDirection_;
        apply.result = cgProduct_;
        apply.slot = kSlotDirectionProduct;
        run(cmd, ApplyPressureOperator, apply, Grid::Level, true);
        finish(cmd, MFX_REDUCE_CG_ALPHA, kSlotDirectionProduct, 0, true);
        shared::PressureDispatch update = push(0);
        update.result = cgPressure_;
        update.source = cgDirection_;
        update.rhs = cgResidual_;
        update.other = cgProduct_;
        update.slot = kSlotCheck;
        run(cmd, UpdateCgSolution, update, Grid::Level, true);
        finish(cmd, MFX_REDUCE_CG_CHECK, kSlotCheck, 0, true);
        if (iteration + 1 < options_.cgMaxIterations) precondition(false);
    }
    shared::PressureDispatch store = push(0);
    store.source = cgPressure_;
    store.flags = MFX_PRESSURE_ZERO_IF_NO_RHS;
    run(cmd, StorePressure, store, Grid::Level, false);
}

} // namespace mfx::fluid
