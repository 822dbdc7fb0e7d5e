#include "fluid/sparse_smoke_solver.h"

#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "fluid/smoke_fields.h"
#include "fluid/stage_dispatches.h"
#include "shaders/embedded.h"
#include "shaders/shared/sparse_fluid.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace mfx::fluid {

namespace {

constexpr VkBufferUsageFlags kFieldUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                           VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                           VK_BUFFER_USAGE_TRANSFER_DST_BIT;
constexpr uint32_t kGroupsPerBrick = 2; // workgroups of 8x8x4

// The sparse stages' SPIR-V by kernel name (shaders/fluid/<name>.comp). A function: the spans are
// defined in another translation unit.
std::span<const uint32_t> kernel(const std::string& name) {
    using namespace mfx::shaders;
    static const std::pair<const char*, std::span<const uint32_t>> kernels[] = {
        {"sparse_activate_bricks", sparse_activate_bricks_comp},
        {"sparse_mark_solids", sparse_mark_solids_comp},
        {"sparse_mark_solid_bricks", sparse_mark_solid_bricks_comp},
        {"sparse_splat_impulses", sparse_splat_impulses_comp},
        {"sparse_advect_velocity", sparse_advect_velocity_comp},
        {"sparse_advect_pigment", sparse_advect_pigment_comp},
        {"sparse_apply_buoyancy", sparse_apply_buoyancy_comp},
        {"sparse_apply_boundaries", sparse_apply_boundaries_comp},
        {"sparse_compute_divergence", sparse_compute_divergence_comp},
        {"sparse_solve_pressure", sparse_solve_pressure_comp},
        {"sparse_project", sparse_project_comp},
        {"sparse_mark_live_bricks", sparse_mark_live_bricks_comp},
        {"sparse_mark_emitter_bricks", sparse_mark_emitter_bricks_comp},
        {"sparse_dilate_bricks", sparse_dilate_bricks_comp},
        {"sparse_free_bricks", sparse_free_bricks_comp},
        {"sparse_allocate_bricks", sparse_allocate_bricks_comp},
    };
    for (const auto& [n, spirv] : kernels)
        if (name == n) return spirv;
    throw std::logic_error("the sparse smoke solver has no kernel " + name);
}

// Brick-local indices, as shaders/fluid/sparse_common.glsl.
size_t brickCell(glm::ivec3 l) {
    return size_t(l.x) + kBrickSize * (size_t(l.y) + kBrickSize * size_t(l.z));
}
size_t brickFace(int c, glm::ivec3 l) {
    glm::ivec3 e{int(kBrickSize)};
    e[c] += 1;
    return size_t(l.x) + size_t(e.x) * (size_t(l.y) + size_t(e.y) * size_t(l.z));
}

// Calls visit(slot, brick origin in cells) for every active brick of a brick table.
template <typename Visit>
void forEachActiveBrick(const std::vector<uint32_t>& table, glm::uvec3 n, Visit visit) {
    for (uint32_t index = 0; index < table.size(); ++index) {
        if (table[index] == kNoSlot) continue;
        const glm::ivec3 b(index % n.x, (index / n.x) % n.y, index / (n.x * n.y));
        visit(table[index], b * int(kBrickSize));
    }
}

// fieldBarrier, and the brick lists' writes (a compute pass, or an upload) before the indirect
// dispatches that read them.
void listBarrier(VkCommandBuffer cmd) {
    fieldBarrier(cmd);
    gpu::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
        VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
}

// Workgroups of 256 invocations covering `count` items.
uint32_t flatGroups(uint32_t count) {
    return (count + 255u) / 256u;
}

// Calls visit(local face, face index in the dense array) for every face a brick stores of
// component c.
template <typename Visit>
void forEachBrickFace(const GridShape& grid, int c, glm::ivec3 origin, Visit visit) {
    const glm::uvec3 dense = faceExtent(grid, c);
    glm::ivec3 e{int(kBrickSize)};
    e[c] += 1;
    for (int z = 0; z < e.z; ++z)
        for (int y = 0; y < e.y; ++y)
            for (int x = 0; x < e.x; ++x) {
                const glm::ivec3 l(x, y, z), q = origin + l;
                visit(l, size_t(q.x) + dense.x * (size_t(q.y) + dense.y * size_t(q.z)));
            }
}

template <typename Visit>
void forEachBrickCell(const GridShape& grid, glm::ivec3 origin, Visit visit) {
    const int s = int(kBrickSize);
    for (int z = 0; z < s; ++z)
        for (int y = 0; y < s; ++y)
            for (int x = 0; x < s; ++x) {
                const glm::ivec3 l(x, y, z), q = origin + l;
                visit(l, grid.index(uint32_t(q.x), uint32_t(q.y), uint32_t(q.z)));
            }
}

} // namespace

Result<std::unique_ptr<SparseSmokeSolver>> SparseSmokeSolver::create(const gpu::Context& ctx,
                                                                     const SolverOptions& options,
                                                                     uint32_t maxBricks,
                                                                     uint32_t initialSlots) {
    const VkPhysicalDeviceLimits& limits = ctx.limits();
    // The virtual domain is never an image: only the buffers' sizes bound it.
    if (Status valid =
            validateSparseOptions(options, 1u << 16, limits.maxComputeWorkGroupInvocations);
        !valid)
        return valid.error();
    if (maxBricks == 0) return Error{"max_bricks must be at least 1"};
    const uint64_t bricks = options.grid.cellCount() / (kBrickSize * kBrickSize * kBrickSize);
    if (bricks > (uint64_t(1) << 26))
        return Error{"the sparse domain " + toString(options.grid) + " has " +
                     std::to_string(bricks) + " bricks; at most " +
                     std::to_string(uint64_t(1) << 26) + " are addressed"};
    // The largest atlas buffer, the pigment, holds 8 KiB a brick.
    const uint64_t perBuffer = uint64_t(limits.maxStorageBufferRange) / (MFX_BRICK_CELLS * 16u);
    if (maxBricks > perBuffer)
        return Error{"max_bricks " + std::to_string(maxBricks) + " exceeds the " +
                     std::to_string(perBuffer) +
                     " bricks one storage buffer of this device can hold"};
    return std::unique_ptr<SparseSmokeSolver>(
        new SparseSmokeSolver(ctx, options, maxBricks, initialSlots));
}

SparseSmokeSolver::SparseSmokeSolver(const gpu::Context& ctx, const SolverOptions& options,
                                     uint32_t maxBricks, uint32_t initialSlots)
    : ctx_(ctx), options_(options),
      layout_(glm::uvec3(options.grid.cellsX, options.grid.cellsY, options.grid.cellsZ) /
                  kBrickSize,
              maxBricks, initialSlots) {
    parameters_ =
        gpu::createBuffer(ctx, sizeof(shared::FluidParameters), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                          gpu::MemoryUsage::Upload, "sparse fluid parameters");
    ownEmitters_ = gpu::createBuffer(ctx, 16 * sizeof(shared::FluidEmitter),
                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload,
                                     "sparse fluid emitters");
    emitterBuffer_ = ownEmitters_.get();
    emitterBufferSize_ = ownEmitters_.size;
    table_ =
        gpu::createBuffer(ctx, layout_.table().size() * sizeof(uint32_t),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                              VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          gpu::MemoryUsage::DeviceLocal, "sparse brick table");
    uploadBuffer(ctx, table_, std::span<const uint32_t>(layout_.table()));
    const VkDeviceSize perBrick = layout_.table().size() * sizeof(uint32_t);
    for (gpu::Buffer* b : {&brickState_, &wantedScratch_})
        *b = gpu::createBuffer(
            ctx, perBrick, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
            gpu::MemoryUsage::DeviceLocal, "sparse brick marks");
    // The refused bricks and the half-bricks with live pigment.
    refused_ = gpu::createBuffer(ctx, 2 * sizeof(uint32_t), kFieldUsage,
                                 gpu::MemoryUsage::DeviceLocal, "sparse rebuild counts");
    counters_ = gpu::createBuffer(ctx, 5 * sizeof(uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  gpu::MemoryUsage::Readback, "sparse rebuild counts");
    rebuildParameters_ = gpu::createBuffer(ctx, sizeof(shared::SparseRebuildParameters),
                                           VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                           gpu::MemoryUsage::Upload, "sparse rebuild parameters");
    noSolids_ = gpu::createBuffer(ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  gpu::MemoryUsage::DeviceLocal, "sparse no solids");
    allocateAtlas(layout_.capacity());
    uploadList(active_, {});
    uploadList(activated_, {});
    writeParameters();
}

gpu::Program& SparseSmokeSolver::program(const char* name, uint32_t target, uint32_t variant) {
    const bool solids = !solids_.empty();
    gpu::Program& slot = programs_[{name, target, variant, solids}];
    if (slot.pipeline() != VK_NULL_HANDLE) return slot;
    gpu::ComputeProgramDesc desc;
    desc.name = name;
    desc.spirv = kernel(name);
    desc.pushConstantSize = sizeof(shared::FluidDispatch);
    // Constant ids as in shaders/fluid/fluid_common.glsl: the target, the six boundary kinds, the
    // integrator, the workgroup (8x8x4: half a brick), the kernel's variant, then whether solids
    // are set (shaders/fluid/sparse_solids.glsl).
    desc.specialization = {target};
    for (const FaceBoundary& face : options_.boundaries)
        desc.specialization.push_back(uint32_t(face.kind));
    desc.specialization.push_back(uint32_t(options_.integrator));
    desc.specialization.insert(
        desc.specialization.end(),
        {kBrickSize, kBrickSize, kBrickSize / kGroupsPerBrick, variant, solids ? 1u : 0u});
    slot = gpu::createComputeProgram(ctx_, desc);
    return slot;
}

void SparseSmokeSolver::allocateAtlas(uint32_t slots) {
    auto make = [&](VkDeviceSize bytes, const char* name) {
        return gpu::createBuffer(ctx_, bytes, kFieldUsage, gpu::MemoryUsage::DeviceLocal, name);
    };
    const VkDeviceSize faces = VkDeviceSize(slots) * MFX_BRICK_FACES * sizeof(float);
    const VkDeviceSize cells = VkDeviceSize(slots) * MFX_BRICK_CELLS * sizeof(float);
    std::array<std::array<gpu::Buffer, 3>, 2> velocity;
    std::array<gpu::Buffer, 2> pigment, pressure;
    for (int set = 0; set < 2; ++set) {
        for (int c = 0; c < 3; ++c)
            velocity[set][c] = make(faces, "sparse velocity");
        pigment[set] = make(4 * cells, "sparse pigment");
        pressure[set] = make(cells, "sparse pressure");
    }
    gpu::Buffer divergence = make(cells, "sparse divergence");
    // The holders need not be kept: every sub-step marks them before a stage reads them.
    if (solidHolders_.get() != VK_NULL_HANDLE) solidHolders_ = make(cells, "sparse solid holders");
    const VkDeviceSize listBytes = sizeof(shared::BrickListHeader) + VkDeviceSize(slots) * 4;
    auto makeList = [&](const char* name) {
        return gpu::createBuffer(ctx_, listBytes,
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                     VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | kFieldUsage,
                                 gpu::MemoryUsage::DeviceLocal, name);
    };
    gpu::Buffer active = makeList("sparse active bricks");
    gpu::Buffer activated = makeList("sparse activated bricks");
    gpu::Buffer freeSlots = makeList("sparse free slots");
    if (slots_ > 0) { // keep what the old atlas held: slots keep their numbers
        gpu::submitOneShot(ctx_, [&](VkCommandBuffer cmd) {
            auto copy = [&](const gpu::Buffer& from, const gpu::Buffer& to) {
                const VkBufferCopy region{0, 0, from.size};
                vkCmdCopyBuffer(cmd, from.get(), to.get(), 1, &region);
            };
            for (int set = 0; set < 2; ++set) {
                for (int c = 0; c < 3; ++c)
                    copy(velocity_[set][c], velocity[set][c]);
                copy(pigment_[set], pigment[set]);
                copy(pressure_[set], pressure[set]);
            }
            copy(divergence_, divergence);
            copy(active_, active);
            copy(activated_, activated);
            copy(freeSlots_, freeSlots);
        });
    }
    velocity_ = std::move(velocity);
    pigment_ = std::move(pigment);
    pressure_ = std::move(pressure);
    divergence_ = std::move(divergence);
    active_ = std::move(active);
    activated_ = std::move(activated);
    freeSlots_ = std::move(freeSlots);
    slots_ = slots;
}

std::vector<uint32_t> SparseSmokeSolver::activeBricks() const {
    return activeBricksOf(slotTable());
}

std::vector<uint8_t> SparseSmokeSolver::activeCells() const {
    return activeCellsOf(slotTable(), layout_.bricks());
}

std::vector<uint32_t> SparseSmokeSolver::slotTable() const {
    return gpuLayout_ ? gpu::readBufferAs<uint32_t>(ctx_, table_) : layout_.table();
}

void SparseSmokeSolver::uploadList(gpu::Buffer& list, const std::vector<uint32_t>& bricks) {
    std::vector<uint32_t> words(4 + bricks.size());
    words[0] = uint32_t(bricks.size()) * kGroupsPerBrick;
    words[1] = 1;
    words[2] = 1;
    words[3] = uint32_t(bricks.size());
    std::copy(bricks.begin(), bricks.end(), words.begin() + 4);
    uploadBuffer(ctx_, list, std::span<const uint32_t>(words));
}

SparseBricks::Update SparseSmokeSolver::commitActive() {
    if (gpuLayout_)
        throw std::logic_error("commitActive: the GPU rebuilds this solver's active set");
    SparseBricks::Update update = layout_.commit();
    if (layout_.capacity() > slots_) allocateAtlas(layout_.capacity());
    uploadBuffer(ctx_, table_, std::span<const uint32_t>(layout_.table()));
    uploadList(active_, layout_.activeList());
    activeCount_ = uint32_t(layout_.activeList().size());
    uploadList(activated_, update.activated);
    std::vector<uint32_t> states(layout_.table().size(), 0);
    for (uint32_t index : update.activated)
        states[index] = MFX_BRICK_WANTED | MFX_BRICK_FRESH;
    uploadBuffer(ctx_, brickState_, std::span<const uint32_t>(states));
    if (!update.activated.empty() || !solids_.empty())
        gpu::submitOneShot(ctx_, [&](VkCommandBuffer cmd) {
            if (!update.activated.empty()) recordActivation(cmd);
            // The solids in the new set of cells, as the reference's setActiveCells marks them.
            if (!solids_.empty()) {
                listBarrier(cmd);
                markSolids(cmd);
            }
        });
    return update;
}

void SparseSmokeSolver::recordActivation(VkCommandBuffer cmd) {
    listBarrier(cmd);
    for (uint32_t pass = 0; pass < 2; ++pass) {
        Writes w = common(activated_);
        for (uint32_t c = 0; c < 3; ++c)
            w.push_back(gpu::bindBuffer(3 + c, velocity_[currentVelocity_[c]][c]));
        w.push_back(gpu::bindBuffer(6, pigment_[currentPigment_]));
        w.push_back(gpu::bindBuffer(7, pressure_[currentPressure_]));
        w.push_back(gpu::bindBuffer(8, divergence_));
        w.push_back(gpu::bindBuffer(9, brickState_));
        dispatch(cmd, program("sparse_activate_bricks", 0, pass), w, activated_);
        fieldBarrier(cmd);
    }
}

void SparseSmokeSolver::startGpuLayout() {
    // The free stack: every slot no brick holds, the lowest on top.
    std::vector<uint8_t> used(slots_, 0);
    for (uint32_t slot : layout_.table())
        if (slot != kNoSlot) used[slot] = 1;
    std::vector<uint32_t> stack(1, 0);
    for (uint32_t slot = slots_; slot-- > 0;)
        if (!used[slot]) stack.push_back(slot);
    stack[0] = uint32_t(stack.size() - 1);
    uploadBuffer(ctx_, freeSlots_, std::span<const uint32_t>(stack));
    gpuLayout_ = true;
}

void SparseSmokeSolver::recordRebuild(VkCommandBuffer cmd, float alphaThreshold,
                                      float speedThreshold, uint32_t reachCells) {
    if (!gpuLayout_) startGpuLayout();
    const uint32_t dispatchesBefore = dispatches_;
    const uint32_t bricks = uint32_t(layout_.table().size());
    shared::SparseRebuildParameters rebuild{};
    rebuild.thresholds = glm::vec4(alphaThreshold, speedThreshold, 0.0f, 0.0f);
    rebuild.counts = glm::uvec4((reachCells + kBrickSize - 1) / kBrickSize, bricks, slots_,
                                uint32_t(solids_.size()));
    std::memcpy(rebuildParameters_.mapped, &rebuild, sizeof rebuild);
    writeParameters(); // the emitter count
    listBarrier(cmd);
    vkCmdFillBuffer(cmd, wantedScratch_.get(), 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(cmd, refused_.get(), 0, VK_WHOLE_SIZE, 0);
    listBarrier(cmd);
    // 1-2: the live bricks (over the active list as it was) and the emitters' bricks.
    {
        Writes w = common(active_);
        w.push_back(gpu::bindBuffer(3, rebuildParameters_));
        for (uint32_t c = 0; c < 3; ++c)
            w.push_back(gpu::bindBuffer(4 + c, velocity_[currentVelocity_[c]][c]));
        w.push_back(gpu::bindBuffer(7, pigment_[currentPigment_]));
        w.push_back(gpu::bindBuffer(8, wantedScratch_));
        w.push_back(gpu::bindBuffer(9, refused_));
        dispatch(cmd, program("sparse_mark_live_bricks"), w, active_);
    }
    const Writes rebuildCommon = {gpu::bindBuffer(0, parameters_),
                                  gpu::bindBuffer(1, rebuildParameters_)};
    auto flat = [&](const char* name, uint32_t target, Writes w, uint32_t items) {
        w.insert(w.begin(), rebuildCommon.begin(), rebuildCommon.end());
        gpu::Program& prog = program(name, target);
        prog.bind(cmd, w);
        prog.push(cmd, shared::FluidDispatch{0, 0, 0, 0});
        if (items > 0) vkCmdDispatch(cmd, flatGroups(items), 1, 1);
        dispatches_ += items > 0 ? 1 : 0;
    };
    if (emitterCount_ > 0)
        flat("sparse_mark_emitter_bricks", 0, {emitterWrite(2), gpu::bindBuffer(3, wantedScratch_)},
             emitterCount_);
    listBarrier(cmd);
    // The lists are rebuilt from here on: empty them.
    for (const gpu::Buffer* list : {&active_, &activated_}) {
        vkCmdFillBuffer(cmd, list->get(), 0, 4, 0);
        vkCmdFillBuffer(cmd, list->get(), 4, 8, 1);
        vkCmdFillBuffer(cmd, list->get(), 12, 4, 0);
    }
    // 3: dilation, x then y then z, ending in the brick states.
    const gpu::Buffer* from = &wantedScratch_;
    const gpu::Buffer* to = &brickState_;
    for (uint32_t axis = 0; axis < 3; ++axis) {
        flat("sparse_dilate_bricks", axis, {gpu::bindBuffer(2, *from), gpu::bindBuffer(3, *to)},
             bricks);
        listBarrier(cmd);
        std::swap(from, to);
    }
    // The bricks the solids may reach, not grown: the air the body stirs is live, and the next
    // rebuild grows its bricks as any live ones.
    if (!solids_.empty()) {
        recordSolidsUpload(cmd);
        flat("sparse_mark_solid_bricks", 0,
             {gpu::bindBuffer(2, solidsBuffer_), gpu::bindBuffer(3, brickState_)},
             uint32_t(solids_.size()));
        listBarrier(cmd);
    }
    // 4-5: free, then allocate and list.
    flat("sparse_free_bricks", 0,
         {gpu::bindBuffer(2, table_), gpu::bindBuffer(3, brickState_),
          gpu::bindBuffer(4, freeSlots_)},
         bricks);
    listBarrier(cmd);
    flat("sparse_allocate_bricks", 0,
         {gpu::bindBuffer(2, table_), gpu::bindBuffer(3, brickState_),
          gpu::bindBuffer(4, freeSlots_), gpu::bindBuffer(5, active_),
          gpu::bindBuffer(6, activated_), gpu::bindBuffer(7, refused_)},
         bricks);
    recordActivation(cmd);
    // The counts, for finishRebuild.
    const VkBufferCopy counts[5] = {{0, 0, 4}, {12, 4, 4}, {12, 8, 4}, {0, 12, 4}, {4, 16, 4}};
    vkCmdCopyBuffer(cmd, refused_.get(), counters_.get(), 1, &counts[0]);
    vkCmdCopyBuffer(cmd, refused_.get(), counters_.get(), 1, &counts[4]);
    vkCmdCopyBuffer(cmd, active_.get(), counters_.get(), 1, &counts[1]);
    vkCmdCopyBuffer(cmd, activated_.get(), counters_.get(), 1, &counts[2]);
    vkCmdCopyBuffer(cmd, freeSlots_.get(), counters_.get(), 1, &counts[3]);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    fieldBarrier(cmd);
    lastRebuildDispatches_ = dispatches_ - dispatchesBefore;
}

SparseSmokeSolver::RebuildCounts SparseSmokeSolver::finishRebuild() {
    uint32_t words[5];
    std::memcpy(words, counters_.mapped, sizeof words);
    RebuildCounts counts;
    counts.refused = words[0];
    counts.livePigment = words[4];
    counts.active = words[1];
    activeCount_ = counts.active;
    counts.activated = words[2];
    const uint32_t freeCount = words[3];
    if (counts.refused == 0) return counts;
    const uint32_t budget = layout_.maxBricks();
    if (slots_ >= budget) {
        counts.error = std::to_string(counts.refused) + " wanted bricks over the budget of " +
                       std::to_string(budget) + " (max_bricks); simulating within it";
        return counts;
    }
    const uint32_t grown =
        std::min(budget, std::max(2 * slots_, counts.active + counts.refused + freeCount));
    const uint32_t before = slots_;
    try {
        allocateAtlas(grown);
    } catch (const std::exception& e) {
        counts.error = "the sparse atlas could not grow from " + std::to_string(before) + " to " +
                       std::to_string(grown) + " bricks (" + e.what() + "); simulating with " +
                       std::to_string(before);
        return counts;
    }
    // The new slots onto the free stack, above those already there, the lowest on top.
    std::vector<uint32_t> added;
    for (uint32_t slot = grown; slot-- > before;)
        added.push_back(slot);
    const uint32_t count = freeCount + uint32_t(added.size());
    uploadBuffer(ctx_, freeSlots_, std::span<const uint32_t>(&count, 1));
    uploadBuffer(ctx_, freeSlots_, std::span<const uint32_t>(added),
                 VkDeviceSize(1 + freeCount) * sizeof(uint32_t));
    counts.grown = true;
    return counts;
}

void SparseSmokeSolver::setState(const FieldState& state) {
    const GridShape& g = options_.grid;
    std::array<std::vector<float>, 3> velocity;
    for (auto& v : velocity)
        v.assign(size_t(slots_) * MFX_BRICK_FACES, 0.0f);
    std::vector<float> pigment(size_t(slots_) * MFX_BRICK_CELLS * 4, 0.0f);
    std::vector<float> pressure(size_t(slots_) * MFX_BRICK_CELLS, 0.0f), divergence = pressure;
    const std::vector<float>* faces[3] = {&state.velocityX, &state.velocityY, &state.velocityZ};
    forEachActiveBrick(slotTable(), layout_.bricks(), [&](uint32_t slot, glm::ivec3 origin) {
        for (int c = 0; c < 3; ++c)
            forEachBrickFace(g, c, origin, [&](glm::ivec3 l, size_t dense) {
                velocity[c][slot * MFX_BRICK_FACES + brickFace(c, l)] = (*faces[c])[dense];
            });
        forEachBrickCell(g, origin, [&](glm::ivec3 l, size_t dense) {
            const size_t e = slot * MFX_BRICK_CELLS + brickCell(l);
            pressure[e] = state.pressure[dense];
            divergence[e] = state.divergence[dense];
            for (size_t channel = 0; channel < 4; ++channel)
                pigment[4 * e + channel] = state.pigment[4 * dense + channel];
        });
    });
    for (int c = 0; c < 3; ++c)
        uploadBuffer(ctx_, velocity_[currentVelocity_[c]][c], std::span<const float>(velocity[c]));
    uploadBuffer(ctx_, pigment_[currentPigment_], std::span<const float>(pigment));
    uploadBuffer(ctx_, pressure_[currentPressure_], std::span<const float>(pressure));
    uploadBuffer(ctx_, divergence_, std::span<const float>(divergence));
}

FieldState SparseSmokeSolver::state() {
    const GridShape& g = options_.grid;
    FieldState state = FieldState::zero(g);
    std::array<std::vector<float>, 3> velocity;
    for (int c = 0; c < 3; ++c)
        velocity[c] = gpu::readBufferAs<float>(ctx_, velocity_[currentVelocity_[c]][c]);
    const std::vector<float> pigment = gpu::readBufferAs<float>(ctx_, pigment_[currentPigment_]);
    const std::vector<float> pressure = gpu::readBufferAs<float>(ctx_, pressure_[currentPressure_]);
    const std::vector<float> divergence = gpu::readBufferAs<float>(ctx_, divergence_);
    std::vector<float>* faces[3] = {&state.velocityX, &state.velocityY, &state.velocityZ};
    std::array<std::vector<uint8_t>, 3> seen;
    for (int c = 0; c < 3; ++c)
        seen[c].assign(faces[c]->size(), 0);
    sharedFaceMismatches_ = 0;
    forEachActiveBrick(slotTable(), layout_.bricks(), [&](uint32_t slot, glm::ivec3 origin) {
        for (int c = 0; c < 3; ++c)
            forEachBrickFace(g, c, origin, [&](glm::ivec3 l, size_t dense) {
                const float v = velocity[c][slot * MFX_BRICK_FACES + brickFace(c, l)];
                float& out = (*faces[c])[dense];
                // Bitwise: both copies come from the same code on the same inputs.
                if (seen[c][dense] && std::memcmp(&out, &v, sizeof v) != 0) ++sharedFaceMismatches_;
                out = v;
                seen[c][dense] = 1;
            });
        forEachBrickCell(g, origin, [&](glm::ivec3 l, size_t dense) {
            const size_t e = slot * MFX_BRICK_CELLS + brickCell(l);
            state.pressure[dense] = pressure[e];
            state.divergence[dense] = divergence[e];
            for (size_t channel = 0; channel < 4; ++channel)
                state.pigment[4 * dense + channel] = pigment[4 * e + channel];
        });
    });
    return state;
}

Status SparseSmokeSolver::setEmitters(std::span<const shared::FluidEmitter> emitters) {
    if (Status valid = validateEmitters(emitters); !valid) return valid;
    const VkDeviceSize bytes = emitters.size_bytes();
    if (bytes > ownEmitters_.size)
        ownEmitters_ = gpu::createBuffer(ctx_, std::max<VkDeviceSize>(bytes, 2 * ownEmitters_.size),
                                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         gpu::MemoryUsage::Upload, "sparse fluid emitters");
    if (bytes > 0) std::memcpy(ownEmitters_.mapped, emitters.data(), bytes);
    setEmitterBuffer(ownEmitters_, uint32_t(emitters.size()));
    return Ok{};
}

void SparseSmokeSolver::setEmitterBuffer(const gpu::Buffer& buffer, uint32_t count) {
    emitterBuffer_ = buffer.get();
    emitterBufferSize_ = buffer.size;
    emitterCount_ = std::min<uint32_t>(count, uint32_t(buffer.size / sizeof(shared::FluidEmitter)));
}

gpu::DescriptorWrite SparseSmokeSolver::emitterWrite(uint32_t binding) const {
    gpu::DescriptorWrite w;
    w.binding = binding;
    w.buffer = {emitterBuffer_, 0, emitterBufferSize_};
    return w;
}

void SparseSmokeSolver::writeParameters() {
    const shared::FluidParameters parameters = makeParameters(options_, emitterCount_);
    std::memcpy(parameters_.mapped, &parameters, sizeof(parameters));
}

SparseSmokeSolver::Writes SparseSmokeSolver::common(const gpu::Buffer& list) const {
    return {gpu::bindBuffer(0, parameters_), gpu::bindBuffer(1, table_), gpu::bindBuffer(2, list)};
}

void SparseSmokeSolver::dispatch(VkCommandBuffer cmd, gpu::Program& prog, const Writes& writes,
                                 const gpu::Buffer& list) {
    prog.bind(cmd, writes);
    prog.push(cmd, shared::FluidDispatch{0, 0, 0, 0});
    vkCmdDispatchIndirect(cmd, list.get(), 0);
    ++dispatches_;
}

// --- Solids -------------------------------------------------------------------------------------

Status SparseSmokeSolver::setSolids(std::span<const shared::FluidSolid> solids) {
    if (Status valid = validateGpuSolids(solids, ctx_.limits().maxUniformBufferRange); !valid)
        return valid;
    // Made once and never replaced: a recording in flight may name them.
    if (!solids.empty() && solidsBuffer_.get() == VK_NULL_HANDLE) {
        solidsBuffer_ =
            gpu::createBuffer(ctx_, kMaxGpuSolids * sizeof(shared::FluidSolid),
                              VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                              gpu::MemoryUsage::DeviceLocal, "sparse solids");
        solidHolders_ =
            gpu::createBuffer(ctx_, VkDeviceSize(slots_) * MFX_BRICK_CELLS * sizeof(uint32_t),
                              kFieldUsage, gpu::MemoryUsage::DeviceLocal, "sparse solid holders");
    }
    solids_.assign(solids.begin(), solids.end());
    return Ok{};
}

void SparseSmokeSolver::recordSolidsUpload(VkCommandBuffer cmd) {
    // Into the command buffer itself: steps recorded one after another each mark their own.
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_UNIFORM_READ_BIT,
                       VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    vkCmdUpdateBuffer(cmd, solidsBuffer_.get(), 0, solids_.size() * sizeof(shared::FluidSolid),
                      solids_.data());
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_UNIFORM_READ_BIT);
}

gpu::DescriptorWrite SparseSmokeSolver::solidWrite() const {
    return gpu::bindBuffer(14, solids_.empty() ? noSolids_ : solidHolders_);
}

void SparseSmokeSolver::markSolids(VkCommandBuffer cmd) {
    if (solids_.empty()) return;
    recordSolidsUpload(cmd);
    Writes w = common(active_);
    for (uint32_t c = 0; c < 3; ++c)
        w.push_back(gpu::bindBuffer(3 + c, velocity_[currentVelocity_[c]][c]));
    w.push_back(gpu::bindBuffer(6, pigment_[currentPigment_]));
    w.push_back(gpu::bindBuffer(13, solidsBuffer_));
    w.push_back(solidWrite());
    const shared::FluidDispatch count{uint32_t(solids_.size()), 0, 0, 0};
    for (uint32_t pass = 0; pass < 2; ++pass) { // the holders, then the faces and pigment
        gpu::Program& prog = program("sparse_mark_solids", 0, pass);
        prog.bind(cmd, w);
        prog.push(cmd, count);
        vkCmdDispatchIndirect(cmd, active_.get(), 0);
        ++dispatches_;
        fieldBarrier(cmd);
    }
}

// --- Stages -------------------------------------------------------------------------------------

void SparseSmokeSolver::splatImpulses(VkCommandBuffer cmd) {
    if (emitterCount_ == 0) return;
    Writes w = common(active_);
    w.push_back(solidWrite());
    w.push_back(emitterWrite(3));
    for (uint32_t c = 0; c < 3; ++c)
        w.push_back(gpu::bindBuffer(4 + c, velocity_[currentVelocity_[c]][c]));
    w.push_back(gpu::bindBuffer(7, pigment_[currentPigment_]));
    for (uint32_t target = 0; target < 4; ++target) // each writes only its own field
        dispatch(cmd, program("sparse_splat_impulses", target), w, active_);
    fieldBarrier(cmd);
}

void SparseSmokeSolver::advectVelocity(VkCommandBuffer cmd) {
    for (uint32_t c = 0; c < 3; ++c) {
        Writes w = common(active_);
        w.push_back(solidWrite());
        for (uint32_t d = 0; d < 3; ++d)
            w.push_back(gpu::bindBuffer(3 + d, velocity_[currentVelocity_[d]][d]));
        w.push_back(gpu::bindBuffer(6, velocity_[1 - currentVelocity_[c]][c]));
        dispatch(cmd, program("sparse_advect_velocity", c), w, active_);
    }
    fieldBarrier(cmd);
    for (int& current : currentVelocity_)
        current = 1 - current;
}

void SparseSmokeSolver::advectPigment(VkCommandBuffer cmd) {
    Writes w = common(active_);
    w.push_back(solidWrite());
    for (uint32_t d = 0; d < 3; ++d)
        w.push_back(gpu::bindBuffer(3 + d, velocity_[currentVelocity_[d]][d]));
    w.push_back(gpu::bindBuffer(6, pigment_[currentPigment_]));
    w.push_back(gpu::bindBuffer(7, pigment_[1 - currentPigment_]));
    dispatch(cmd, program("sparse_advect_pigment", uint32_t(MFX_TARGET_PIGMENT)), w, active_);
    fieldBarrier(cmd);
    currentPigment_ = 1 - currentPigment_;
}

void SparseSmokeSolver::applyBuoyancy(VkCommandBuffer cmd) {
    if (options_.buoyancy == 0.0f) return;
    Writes w = common(active_);
    w.push_back(solidWrite());
    w.push_back(gpu::bindBuffer(3, velocity_[currentVelocity_[1]][1]));
    w.push_back(gpu::bindBuffer(4, pigment_[currentPigment_]));
    w.push_back(gpu::bindBuffer(5, velocity_[1 - currentVelocity_[1]][1]));
    dispatch(cmd, program("sparse_apply_buoyancy", 1), w, active_);
    fieldBarrier(cmd);
    currentVelocity_[1] = 1 - currentVelocity_[1];
}

void SparseSmokeSolver::applyBoundaries(VkCommandBuffer cmd) {
    auto wall = [&](int face) {
        const Boundary b = options_.boundaries[size_t(face)].kind;
        return b == Boundary::WallFreeSlip || b == Boundary::WallNoSlip;
    };
    bool any = false;
    for (uint32_t c = 0; c < 3; ++c) {
        if (!wall(int(2 * c)) && !wall(int(2 * c + 1))) continue; // no face of c is on a wall
        Writes w = common(active_);
        for (uint32_t d = 0; d < 3; ++d)
            w.push_back(gpu::bindBuffer(3 + d, velocity_[currentVelocity_[d]][d]));
        dispatch(cmd, program("sparse_apply_boundaries", c), w, active_);
        any = true;
    }
    if (any) fieldBarrier(cmd);
}

void SparseSmokeSolver::computeDivergence(VkCommandBuffer cmd) {
    Writes w = common(active_);
    w.push_back(solidWrite());
    for (uint32_t d = 0; d < 3; ++d)
        w.push_back(gpu::bindBuffer(3 + d, velocity_[currentVelocity_[d]][d]));
    w.push_back(gpu::bindBuffer(6, divergence_));
    dispatch(cmd, program("sparse_compute_divergence"), w, active_);
    fieldBarrier(cmd);
}

void SparseSmokeSolver::solvePressure(VkCommandBuffer cmd) {
    if (!options_.warmStart) {
        const gpu::Buffer& p = pressure_[currentPressure_];
        vkCmdFillBuffer(cmd, p.get(), 0, p.size, 0);
        fieldBarrier(cmd);
    }
    for (uint32_t sweep = 0; sweep < options_.jacobiIterations; ++sweep) {
        Writes w = common(active_);
        w.push_back(solidWrite());
        w.push_back(gpu::bindBuffer(3, divergence_));
        w.push_back(gpu::bindBuffer(4, pressure_[currentPressure_]));
        w.push_back(gpu::bindBuffer(5, pressure_[1 - currentPressure_]));
        dispatch(cmd, program("sparse_solve_pressure"), w, active_);
        fieldBarrier(cmd);
        currentPressure_ = 1 - currentPressure_;
    }
}

void SparseSmokeSolver::project(VkCommandBuffer cmd) {
    for (uint32_t c = 0; c < 3; ++c) {
        Writes w = common(active_);
        w.push_back(solidWrite());
        for (uint32_t d = 0; d < 3; ++d)
            w.push_back(gpu::bindBuffer(3 + d, velocity_[currentVelocity_[d]][d]));
        w.push_back(gpu::bindBuffer(6, pressure_[currentPressure_]));
        w.push_back(gpu::bindBuffer(7, velocity_[1 - currentVelocity_[c]][c]));
        dispatch(cmd, program("sparse_project", c), w, active_);
    }
    fieldBarrier(cmd);
    for (int& current : currentVelocity_)
        current = 1 - current;
}

// --- Recording -----------------------------------------------------------------------------------

void SparseSmokeSolver::recordStageOnly(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer) {
    if (timer) timer->begin(cmd, stageName(stage));
    // A stage the sparse domain does not run (validateSparseOptions refuses its option) has no
    // function: nothing to record.
    if (auto record = stageEntry(stage).sparse) (this->*record)(cmd);
    if (timer) timer->end(cmd);
}

void SparseSmokeSolver::recordStage(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer) {
    writeParameters();
    listBarrier(cmd); // the lists and table written before → the indirect dispatches
    recordStageOnly(cmd, stage, timer);
}

void SparseSmokeSolver::recordStep(VkCommandBuffer cmd, gpu::GpuTimer* timer) {
    writeParameters();
    listBarrier(cmd); // the lists and table written before → the indirect dispatches
    lastStepDispatches_.clear();
    for (uint32_t substep = 0; substep < options_.substeps; ++substep)
        for (Stage stage : stepOrder()) {
            const uint32_t before = dispatches_;
            recordStageOnly(cmd, stage, timer);
            countStageDispatches(lastStepDispatches_, stage, dispatches_ - before);
        }
}

void SparseSmokeSolver::recordSceneStep(VkCommandBuffer cmd, const SettleRules& rules,
                                        gpu::GpuTimer* timer) {
    // Not the dense grid's settling speed (alpha threshold x cell size / dt, 3e-4 m/s at the
    // defaults): the projection leaves air that slow far around the smoke, and bricks kept for
    // it would cost several times the smoke's own (the kick's foot smoke: about 700 bricks
    // against 130). The reach: 8 cells a step, 24 m/s at 5 cm and 60 steps a second.
    if (timer) timer->begin(cmd, "rebuild_bricks");
    recordRebuild(cmd, rules.alphaThreshold, rules.liveSpeed, kBrickSize);
    if (timer) timer->end(cmd);
    recordStep(cmd, timer);
}

StageDispatches SparseSmokeSolver::lastScenePasses() const {
    StageDispatches passes = {{"rebuild_bricks", lastRebuildDispatches_}};
    passes.insert(passes.end(), lastStepDispatches_.begin(), lastStepDispatches_.end());
    return passes;
}

SolverActivity SparseSmokeSolver::finishFrame(const gpu::Buffer&, bool measured, bool stepped,
                                              const SettleRules&) {
    SolverActivity a;
    if (!stepped) return a;
    const RebuildCounts counts = finishRebuild();
    a.activeBricks = counts.active;
    a.refusedBricks = counts.refused;
    a.budgetError = counts.error;
    // With solids the body's bricks stay active and its air stirred as long as it moves, and air
    // without pigment shows nothing: the pigment alone decides, as on a dense grid.
    a.settled = measured && (solids_.empty() ? counts.active == 0 && counts.refused == 0
                                             : counts.livePigment == 0);
    return a;
}

PigmentVolume SparseSmokeSolver::pigmentVolume() const {
    PigmentVolume v;
    v.layout = PigmentLayout::BrickAtlas;
    v.atlas = &pigmentAtlas();
    v.brickTable = &brickTable();
    v.activeList = &activeList();
    v.bytes = uint64_t(activeCount_) * MFX_BRICK_CELLS * 4 * sizeof(float);
    return v;
}

void SparseSmokeSolver::step() {
    gpu::submitOneShot(ctx_, [&](VkCommandBuffer cmd) { recordStep(cmd); });
}

void SparseSmokeSolver::runStage(Stage stage) {
    gpu::submitOneShot(ctx_, [&](VkCommandBuffer cmd) { recordStage(cmd, stage); });
}

uint64_t SparseSmokeSolver::memoryBytes() const {
    uint64_t bytes = divergence_.size + table_.size + active_.size + activated_.size +
                     parameters_.size + ownEmitters_.size + brickState_.size + wantedScratch_.size +
                     freeSlots_.size + refused_.size + counters_.size + rebuildParameters_.size +
                     noSolids_.size + solidHolders_.size + solidsBuffer_.size;
    for (int set = 0; set < 2; ++set) {
        for (const gpu::Buffer& b : velocity_[set])
            bytes += b.size;
        bytes += pigment_[set].size + pressure_[set].size;
    }
    return bytes;
}

} // namespace mfx::fluid
