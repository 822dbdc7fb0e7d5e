// Red-black Gauss-Seidel, multigrid V-cycles and MGPCG on the GPU (gpu_multigrid.h). The
// algorithms are the reference's (fluid/reference/red_black_gauss_seidel.cpp, multigrid.cpp,
// mgpcg.cpp; Trottenberg, Oosterlee, Schueller, "Multigrid", 2001, ch. 2; McAdams, Sifakis,
// Teran, "A Parallel Multigrid Poisson Solver for Fluids Simulation on Large Grids", SCA 2010;
// Saad, "Iterative Methods for Sparse Linear Systems", 2003, alg. 9.1), recorded as dispatches of
// the kernels in shaders/{load_pressure_system,relax_colour,compute_residual,restrict_residual,
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

// Partial-sum slots (shaders/pressure_partial_sums.glsl); finish_reduction reads a slot and the
// next one.
constexpr uint32_t kSlotRhsSum = 0;           // sum b (its mean)
constexpr uint32_t kSlotRhsSquares = 1;       // (b, b)
constexpr uint32_t kSlotResidualSquares = 2;  // (r, r), CG's first residual
constexpr uint32_t kSlotResidualSum = 3;      // sum r (its mean)
constexpr uint32_t kSlotDirectionProduct = 4; // (d, A d)
constexpr uint32_t kSlotCheck = 5;            // (r, r) after an update
constexpr uint32_t kSlotPreconditioned = 6;   // (r, z), sum z, sum r
constexpr uint32_t kSlots = 8;

// Rows (y) and layers (z) of a brick, the elements one invocation handles
// (shaders/pressure_solve_common.glsl, levelBrick).
constexpr uint32_t kBrickRows = 4;
constexpr uint32_t kBrickLayers = 4;

// The coarse levels' V-cycle (cycle_coarse_levels.comp) runs in one workgroup of kFusedGroup
// invocations (one SIMD row of a CPU driver: a barrier costs the more, the more invocations
// wait at it) on the levels of at most kFusedBricks bricks (16^3 cells). Measured on lavapipe at
// 64^3: levels 16^3 to 2^3 as separate dispatches cost 2.4 ms per V-cycle, in one dispatch of 256
// invocations 2.6 ms, of 8 invocations 0.8 ms.
constexpr uint32_t kFusedGroup = 8;
constexpr uint32_t kFusedBricks = 64;

int vec4Elements(glm::ivec3 cells) {
    return (cells.x + 3) / 4 * cells.y * cells.z;
}

// The reference's hierarchy cell counts (Multigrid's constructor), without building it: the
// coarsest level's cells.
glm::ivec3 coarsestCells(glm::ivec3 n, uint32_t levels) {
    size_t count = 1;
    auto canHalve = [](int cells) { return cells >= 3; };
    while (canHalve(n.x) || canHalve(n.y) || canHalve(n.z)) {
        if (levels != 0 && count >= levels) break;
        for (int a = 0; a < 3; ++a)
            if (canHalve(n[a])) n[a] = (n[a] + 1) / 2;
        ++count;
    }
    return n;
}

} // namespace

Result<std::unique_ptr<GpuMultigrid>> GpuMultigrid::create(const gpu::Context& ctx,
                                                           const SolverOptions& options) {
    const glm::ivec3 cells(options.grid.cellsX, options.grid.cellsY, options.grid.cellsZ);
    if (options.pressureSolver != PressureSolver::RedBlackGaussSeidel) {
        const glm::ivec3 coarsest = coarsestCells(cells, options.multigrid.levels);
        const uint64_t count = uint64_t(coarsest.x) * coarsest.y * coarsest.z;
        if (count > kMaxCoarsestCells)
            return Error{"multigrid levels = " + std::to_string(options.multigrid.levels) +
                         " leaves a coarsest grid of " + std::to_string(coarsest.x) + "x" +
                         std::to_string(coarsest.y) + "x" + std::to_string(coarsest.z) +
                         " cells; the GPU solver solves a coarsest grid of at most " +
                         std::to_string(kMaxCoarsestCells) +
                         " cells exactly (use more levels, or 0 for the full hierarchy)"};
    }
    // Every vector of every level in one storage buffer: at most 4/3 of level 0 per vector kind,
    // four kinds per level plus four for CG.
    const uint64_t level0 = uint64_t(vec4Elements(cells)) * 16;
    const uint64_t estimate = level0 * 8 * 4 / 3 + 16 * 64;
    if (estimate > ctx.limits().maxStorageBufferRange)
        return Error{"grid " + std::to_string(cells.x) + "x" + std::to_string(cells.y) + "x" +
                     std::to_string(cells.z) + " is too large for the GPU pressure solver \"" +
                     pressureSolverName(options.pressureSolver) + "\" (" +
                     std::to_string(estimate >> 20) + " MiB of vectors; the device's storage " +
                     "buffers hold " + std::to_string(ctx.limits().maxStorageBufferRange >> 20) +
                     " MiB): use \"jacobi\""};
    return std::unique_ptr<GpuMultigrid>(new GpuMultigrid(ctx, options));
}

GpuMultigrid::GpuMultigrid(const gpu::Context& ctx, const SolverOptions& options)
    : ctx_(ctx), options_(options) {
    const glm::ivec3 cells(options.grid.cellsX, options.grid.cellsY, options.grid.cellsZ);
    const PressureGrid finest = PressureGrid::finest(cells, options.boundaries);
    singular_ = finest.singular();
    // Red-black Gauss-Seidel needs level 0 alone (and no coarsest solve).
    std::unique_ptr<Multigrid> hierarchy;
    if (options.pressureSolver != PressureSolver::RedBlackGaussSeidel)
        hierarchy = std::make_unique<Multigrid>(finest, options.multigrid.levels);
    const size_t levelCount = hierarchy ? hierarchy->levelCount() : 1;
    auto grid = [&](size_t l) -> const PressureGrid& {
        return hierarchy ? hierarchy->level(l) : finest;
    };

    // Vectors: per level x (two), b, r; level 0 also CG's four.
    int next = 0;
    auto allocate = [&](int elements) {
        const int at = next;
        next += elements;
        return at;
    };
    for (size_t l = 0; l < levelCount; ++l) {
        Level level;
        level.cells = grid(l).cells();
        level.rowLength = (level.cells.x + 3) / 4;
        level.elements = vec4Elements(level.cells);
        level.x = {allocate(level.elements), allocate(level.elements)};
        level.b = allocate(level.elements);
        level.r = allocate(level.elements);
        levels_.push_back(level);
    }
    if (options.pressureSolver == PressureSolver::MultigridPcg) {
        cgPressure_ = allocate(levels_[0].elements);
        cgResidual_ = allocate(levels_[0].elements);
        cgDirection_ = allocate(levels_[0].elements);
        cgProduct_ = allocate(levels_[0].elements);
    }

    // Tables: per level its axes' cells, and (but the coarsest) its restrictions onto the next.
    std::vector<shared::MultigridLevel> levelTable(levelCount);
    std::vector<shared::MultigridAxisCell> axisTable;
    std::vector<shared::MultigridRestriction> restrictionTable;
    std::vector<float> coarsestTable;
    // Along each axis of each level but the coarsest: the side (-1, 0, +1) of the second coarse
    // index a fine index interpolates from, by the reference's rule (the sign of the fine centre's
    // offset from its parent's centre): with it a wrapped index can be unwrapped.
    auto sides = [&](size_t l, int a) {
        auto centres = [](const std::vector<double>& widths) {
            std::vector<double> x(widths.size());
            double start = 0.0;
            for (size_t i = 0; i < widths.size(); ++i) {
                x[i] = start + 0.5 * widths[i];
                start += widths[i];
            }
            return x;
        };
        const std::vector<double> fine = centres(grid(l).widths(a));
        const std::vector<double> coarse = centres(grid(l + 1).widths(a));
        std::vector<int> side(fine.size(), 0);
        for (size_t i = 0; i < fine.size(); ++i) {
            const Multigrid::Interpolation& in = hierarchy->interpolation(l, a)[i];
            const double offset = fine[i] - coarse[size_t(in.coarse[0])];
            side[i] = in.coarse[1] < 0 || offset == 0.0 ? 0 : offset > 0.0 ? 1 : -1;
        }
        return side;
    };
    for (size_t l = 0; l < levelCount; ++l) {
        const PressureGrid& g = grid(l);
        const bool coarsest = l + 1 == levelCount;
        shared::MultigridLevel& entry = levelTable[l];
        entry.cells = glm::ivec4(g.cells(), levels_[l].rowLength);
        entry.vectors = {levels_[l].x[0], levels_[l].x[1], levels_[l].b, levels_[l].r};
        entry.axisCells.w = int(g.size());
        for (int a = 0; a < 3; ++a) {
            entry.axisCells[a] = int(axisTable.size());
            const int n = g.cells()[a];
            const int padded = a == 0 ? 4 * levels_[l].rowLength : n;
            const std::vector<int> side = coarsest ? std::vector<int>() : sides(l, a);
            for (int i = 0; i < padded; ++i) {
                shared::MultigridAxisCell cell{glm::vec4(0.0f), glm::ivec4(-1), glm::vec4(0.0f)};
                if (i < n) {
                    const PressureGrid::Side& low = g.side(a, false, i);
                    const PressureGrid::Side& high = g.side(a, true, i);
                    cell.coefficients =
                        glm::vec4(float(g.widths(a)[size_t(i)]), float(low.inverseDistance),
                                  float(high.inverseDistance), 0.0f);
                    cell.neighbours.x = low.neighbour;
                    cell.neighbours.y = high.neighbour;
                    if (!coarsest) {
                        const Multigrid::Interpolation& in =
                            hierarchy->interpolation(l, a)[size_t(i)];
                        cell.neighbours.z = in.coarse[0];
                        cell.neighbours.w = in.coarse[1];
                        cell.interpolation = glm::vec4(float(in.weight[0]), float(in.weight[1]),
                                                       float(side[size_t(i)]), 0.0f);
                    }
                }
                axisTable.push_back(cell);
            }
            if (coarsest) continue;
            // Prolongation slots: a brick's fine indices interpolate from the coarse indices
            // parent(first) - 1 onwards (prolong_correction.comp).
            const int brick = a == 0 ? 4 : a == 1 ? int(kBrickRows) : int(kBrickLayers);
            for (int first = 0; first < n; first += brick) {
                const int base = hierarchy->interpolation(l, a)[size_t(first)].coarse[0] - 1;
                for (int i = first; i < std::min(n, first + brick); ++i) {
                    const int parent = hierarchy->interpolation(l, a)[size_t(i)].coarse[0];
                    prolongSlots_ = std::max(prolongSlots_, parent + side[size_t(i)] - base + 1);
                }
            }
        }
        if (coarsest) continue;
        // Per coarse index, the fine indices restricting to it: R0 (the cells it covers, weight
        // 1; unused entries -1) and P^T (every fine index interpolated from it, with that
        // weight, unwrapped across a periodic face, in increasing order; unused entries repeat
        // the first with weight 0).
        const glm::ivec3 coarseCells = grid(l + 1).cells();
        for (int kind = 0; kind < 2; ++kind)
            for (int a = 0; a < 3; ++a) {
                (kind == 0 ? entry.restrictSum : entry.restrictTranspose)[a] =
                    int(restrictionTable.size());
                const int n = g.cells()[a];
                std::vector<std::vector<std::pair<int, double>>> lists(size_t(coarseCells[a]));
                const std::vector<int> side = sides(l, a);
                for (int i = 0; i < n; ++i) {
                    const Multigrid::Interpolation& in = hierarchy->interpolation(l, a)[size_t(i)];
                    if (kind == 0) {
                        lists[size_t(hierarchy->parents(l, a)[size_t(i)])].emplace_back(i, 1.0);
                        continue;
                    }
                    lists[size_t(in.coarse[0])].emplace_back(i, in.weight[0]);
                    if (in.coarse[1] < 0) continue;
                    const int unwrapped = in.coarse[0] + side[size_t(i)];
                    const int shift = unwrapped < 0 ? n : unwrapped >= coarseCells[a] ? -n : 0;
                    lists[size_t(in.coarse[1])].emplace_back(i + shift, in.weight[1]);
                }
                const int brick = a == 0 ? 4 : a == 1 ? int(kBrickRows) : int(kBrickLayers);
                for (size_t c = 0; c < lists.size(); ++c) {
                    auto& list = lists[c];
                    if (list.size() > 4)
                        throw std::logic_error("multigrid restriction: more than four fine cells");
                    std::sort(list.begin(), list.end());
                    shared::MultigridRestriction r{glm::ivec4(-1), glm::vec4(0.0f)};
                    for (size_t k = 0; k < 4; ++k) {
                        r.fine[int(k)] = k < list.size() ? list[k].first
                                         : kind == 0     ? -1
                                                         : list.front().first;
                        r.weight[int(k)] = k < list.size() ? float(list[k].second) : 0.0f;
                    }
                    restrictionTable.push_back(r);
                    // P^T slots: a coarse brick's fine indices from its first one's first on.
                    if (kind == 1) {
                        const int base = lists[c - c % size_t(brick)].front().first;
                        int& slots = a == 0 ? restrictSlotsX_ : restrictSlotsYZ_;
                        slots = std::max(slots, list.back().first - base + 1);
                    }
                }
            }
    }
    if (hierarchy) {
        // The coarsest level's exact solution operator, column by column: the reference's
        // solveCoarsest (linear in b) applied to each unit vector.
        const Eigen::Index n = hierarchy->level(levelCount - 1).size();
        levelTable.back().restrictTranspose.w = 0;
        coarsestTable.assign(size_t(n * n), 0.0f);
        for (Eigen::Index j = 0; j < n; ++j) {
            Eigen::ArrayXd unit = Eigen::ArrayXd::Zero(n);
            unit[j] = 1.0;
            const Eigen::ArrayXd column = hierarchy->solveCoarsest(unit);
            for (Eigen::Index i = 0; i < n; ++i)
                coarsestTable[size_t(i * n + j)] = float(column[i]);
        }
    }
    if (restrictionTable.empty()) restrictionTable.push_back({glm::ivec4(-1), glm::vec4(0.0f)});
    if (coarsestTable.empty()) coarsestTable.push_back(0.0f);

    auto table = [&](const auto& values, const char* name) {
        const VkDeviceSize bytes = values.size() * sizeof(values[0]);
        gpu::Buffer buffer = gpu::createBuffer(ctx, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                               gpu::MemoryUsage::Upload, name);
        std::memcpy(buffer.mapped, values.data(), bytes);
        return buffer;
    };
    levelTable_ = table(levelTable, "multigrid levels");
    axisCells_ = table(axisTable, "multigrid axis cells");
    restrictions_ = table(restrictionTable, "multigrid restrictions");
    coarsestMatrix_ = table(coarsestTable, "multigrid coarsest solve");

    partialGroups_ = levelGroups(0);
    partialsPerSlot_ = partialGroups_.x * partialGroups_.y * partialGroups_.z;

    vectors_ =
        gpu::createBuffer(ctx, VkDeviceSize(next) * 16,
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          gpu::MemoryUsage::DeviceLocal, "multigrid vectors");
    partials_ = gpu::createBuffer(ctx, VkDeviceSize(kSlots) * partialsPerSlot_ * 16,
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::DeviceLocal,
                                  "pressure partial sums");
    scalars_ =
        gpu::createBuffer(ctx, sizeof(shared::PressureScalars),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                              VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          gpu::MemoryUsage::DeviceLocal, "pressure scalars");
    // Indirect dispatches: one per level (its bricks), one workgroup.
    std::vector<glm::uvec4> arguments;
    for (size_t l = 0; l < levels_.size(); ++l)
        arguments.emplace_back(levelGroups(l), 0u);
    arguments.emplace_back(1u, 1u, 1u, 0u);
    // The coarse levels cycle in one dispatch.
    fusedLevel_ = levels_.size() - 1;
    for (size_t l = levels_.size(); l-- > 0;) {
        const glm::uvec3 bricks = levelBricks(l);
        if (bricks.x * bricks.y * bricks.z > kFusedBricks) break;
        fusedLevel_ = l;
    }
    argumentsTemplate_ = gpu::createBuffer(ctx, arguments.size() * sizeof(glm::uvec4),
                                           VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                           gpu::MemoryUsage::Upload, "pressure dispatch template");
    std::memcpy(argumentsTemplate_.mapped, arguments.data(), argumentsTemplate_.size);
    arguments_ =
        gpu::createBuffer(ctx, argumentsTemplate_.size,
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                              VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          gpu::MemoryUsage::DeviceLocal, "pressure dispatches");

    // The padding cells of every vector stay 0 from here on (every kernel writes them as 0 or
    // leaves them).
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, vectors_.get(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, scalars_.get(), 0, VK_WHOLE_SIZE, 0);
    });
}

uint64_t GpuMultigrid::memoryBytes() const {
    uint64_t bytes = 0;
    for (const gpu::Buffer* b :
         {&levelTable_, &axisCells_, &restrictions_, &coarsestMatrix_, &vectors_, &partials_,
          &scalars_, &arguments_, &argumentsTemplate_})
        bytes += b->size;
    return bytes;
}

uint32_t GpuMultigrid::lastIterations() const {
    switch (options_.pressureSolver) {
    case PressureSolver::MultigridPcg: {
        const auto scalars = gpu::readBufferAs<shared::PressureScalars>(ctx_, scalars_);
        return scalars.at(0).iterations;
    }
    case PressureSolver::Multigrid:
        return options_.multigrid.cycles;
    default:
        return options_.jacobiIterations;
    }
}

// --- Programs and dispatches ---------------------------------------------------------------------

gpu::Program& GpuMultigrid::program(Kernel kernel) {
    gpu::Program& slot = programs_[size_t(kernel)];
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
    // 8: the V-cycle's kind (MGPCG's symmetric one, or the multigrid solver's).
    const bool fused = kernel == CycleCoarseLevels;
    desc.specialization = {fused ? kFusedGroup : options_.workgroup[0],
                           fused ? 1u : options_.workgroup[1],
                           fused ? 1u : options_.workgroup[2],
                           kBrickRows,
                           kBrickLayers,
                           uint32_t(prolongSlots_),
                           uint32_t(restrictSlotsX_),
                           uint32_t(restrictSlotsYZ_),
                           options_.pressureSolver == PressureSolver::MultigridPcg ? 1u : 0u};
    slot = gpu::createComputeProgram(ctx_, desc);
    return slot;
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
    return {uint32_t(level.rowLength), gpu::groupCount(uint32_t(level.cells.y), kBrickRows),
            gpu::groupCount(uint32_t(level.cells.z), kBrickLayers)};
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
    // Every kernel binds the same resources (shaders/pressure_solve_common.glsl).
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
    };
    prog.bind(cmd, writes);
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
                              const gpu::Image& pressure, const gpu::Buffer& out) {
    divergence_ = &divergence;
    pressure_ = &pressure;
    out_ = &out;
    dispatches_ = 0;
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

    shared::PressureDispatch residual = push(int(l));
    residual.source = level.x[size_t(level.current)];
    residual.rhs = rhs;
    residual.result = level.r;
    run(cmd, ComputeResidual, residual, Grid::Level, indirect);

    // On the coarse level's elements; the coarse correction starts at 0.
    shared::PressureDispatch restriction = push(int(l));
    restriction.source = level.r;
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
    if (singular_) finish(cmd, MFX_REDUCE_MEAN, kSlotRhsSum, 0, false);
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
