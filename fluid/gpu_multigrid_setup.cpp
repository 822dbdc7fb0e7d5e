// The GPU multigrid's set-up (gpu_multigrid.h): the level hierarchy of the reference
// (fluid/reference/multigrid.cpp) laid out in buffers the kernels index, the coarsest level's
// exact solve, and the memory it takes. The recording of the solvers is in gpu_multigrid.cpp.
#include "fluid/gpu_multigrid.h"

#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "fluid/reference/pressure_equation.h"

#include <algorithm>
#include <cstring>

namespace mfx::fluid {

namespace {

// Partial-sum slots per reduction (shaders/fluid/pressure_partial_sums.glsl; gpu_multigrid.cpp
// names them).
constexpr uint32_t kSlots = 8;

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
    : ctx_(ctx), options_(options), brick_(multigridBrick(options.multigrid.brick, ctx)) {
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
        const std::vector<double> fine = cellCentres(grid(l).widths(a));
        const std::vector<double> coarse = cellCentres(grid(l + 1).widths(a));
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
            const int brick = a == 0 ? 4 : int(brick_);
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
                const int brick = a == 0 ? 4 : int(brick_);
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
    // The coarse levels (of at most MultigridOptions::coarseCells cells; why: gpu_multigrid.cpp,
    // kCpuCoarseGroup) cycle in one dispatch of one workgroup (cycle_coarse_levels.comp).
    const uint64_t fusedCells = coarseCycleCells(options_.multigrid.coarseCells);
    fusedLevel_ = levels_.size() - 1;
    for (size_t l = levels_.size(); l-- > 0;) {
        const glm::uvec3 bricks = levelBricks(l);
        if (uint64_t(bricks.x) * 4 * bricks.y * brick_ * bricks.z * brick_ > fusedCells) break;
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

} // namespace mfx::fluid
