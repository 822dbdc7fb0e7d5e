#include "fluid/smoke_solver.h"

#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "fluid/stage_dispatches.h"
#include "shaders/shared/fluid.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

namespace mfx::fluid {

namespace {

gpu::DescriptorWrite storage(uint32_t binding, const gpu::Image& image) {
    return gpu::bindImage(binding, image, VK_IMAGE_LAYOUT_GENERAL);
}

} // namespace

constexpr uint32_t kSolidBlockLists = MFX_SOLID_BLOCK_LISTS;
constexpr uint32_t kSolidListEntries = MFX_SOLID_LIST_ENTRIES;
// A block list's uniform window (fluid_solids.glsl): its entries, four to a uvec4.
constexpr VkDeviceSize kSolidListBytes = kSolidListEntries * sizeof(uint32_t);
// mark_solids.comp's uniform buffers: kMaxSolids solids, 4,096 box blocks (uvec4 each).
constexpr uint32_t kSolidUniformBytes = 65536;
constexpr uint32_t kBoxBlocksAPass = kSolidUniformBytes / (4 * sizeof(uint32_t));

static_assert(SmokeSolver::kMaxSolids * sizeof(shared::FluidSolid) == kSolidUniformBytes,
              "mark_solids.comp's uniform buffer of solids");
static_assert(SmokeSolver::kMaxSolids == 1024, "shaders/fluid/mark_solids.comp's kMaxSolids");

bool storesDirect(StorePath path, const gpu::Context& ctx) {
    return path == StorePath::Direct || (path == StorePath::Auto && !ctx.info().isCpu());
}

bool splitsSolids(ByDevice choice, const gpu::Context& ctx) {
    return choice == ByDevice::On || (choice == ByDevice::Auto && ctx.info().isCpu());
}

Result<std::unique_ptr<SmokeSolver>> SmokeSolver::create(const gpu::Context& ctx,
                                                         const SolverOptions& options) {
    // Faces need one more texel than cells along their axis.
    const VkPhysicalDeviceLimits& limits = ctx.limits();
    if (Status valid = validateOptions(options, limits.maxImageDimension3D - 1,
                                       limits.maxComputeWorkGroupInvocations);
        !valid)
        return valid.error();
    for (int axis = 0; axis < 3; ++axis)
        if (options.workgroup[axis] > limits.maxComputeWorkGroupSize[axis])
            return Error{"workgroup size " + std::to_string(options.workgroup[axis]) + " along " +
                         std::string(1, "xyz"[axis]) + " exceeds the device's limit of " +
                         std::to_string(limits.maxComputeWorkGroupSize[axis])};
    for (VkFormat format : {scalarFormat(options), rgbaFormat(options)}) {
        VkFormatProperties properties{};
        vkGetPhysicalDeviceFormatProperties(ctx.physicalDevice(), format, &properties);
        const VkFormatFeatureFlags needed =
            VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
            VK_FORMAT_FEATURE_TRANSFER_SRC_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
        if ((properties.optimalTilingFeatures & needed) != needed)
            return Error{std::string("the device cannot keep ") +
                         (format == rgbaFormat(options) ? "pigment" : "velocity and pressure") +
                         " in " + storageName(options.storage) + " storage images (format " +
                         std::to_string(int(format)) + ")"};
    }
    // Red-black Gauss-Seidel, multigrid and MGPCG (fluid/gpu_multigrid.h).
    std::unique_ptr<GpuMultigrid> multigrid;
    if (options.pressureSolver != PressureSolver::Jacobi) {
        auto made = GpuMultigrid::create(ctx, options);
        if (!made) return made.error();
        multigrid = std::move(made).value();
    }
    auto solver = std::unique_ptr<SmokeSolver>(new SmokeSolver(ctx, options));
    solver->multigrid_ = std::move(multigrid);
    return solver;
}

SmokeSolver::SmokeSolver(const gpu::Context& ctx, const SolverOptions& options)
    : ctx_(ctx), options_(options), fields_(ctx, options), programs_(ctx, options),
      direct_(fluid::storesDirect(options.storePath, ctx)),
      splitSolids_(fluid::splitsSolids(options.solidLists, ctx)) {
    // A block list packs a block's coordinates into 11, 11 and 10 bits (fluid_solids.glsl), a
    // brick list a brick's into 10 each (at most 4096 cells along an axis: 1024 bricks).
    const glm::uvec3 blocks = solidBlockGrid();
    if (blocks.x > 2048 || blocks.y > 2048 || blocks.z > 1024 ||
        blocks.x * blocks.y * blocks.z > kSolidListEntries ||
        ctx.limits().maxUniformBufferRange < kSolidListBytes)
        splitSolids_ = false; // a list holds at most kSolidListEntries blocks
    // The fused vorticity pass keeps a vec4 per cell of its workgroup's block and ring.
    const std::array<uint32_t, 3>& g = options.workgroup;
    const uint64_t tileBytes = uint64_t(g[0] + 2) * (g[1] + 2) * (g[2] + 2) * 4 * sizeof(float);
    fusedVorticity_ = direct_ && tileBytes <= ctx.limits().maxComputeSharedMemorySize;
    parameters_ =
        gpu::createBuffer(ctx, sizeof(shared::FluidParameters), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                          gpu::MemoryUsage::Upload, "fluid parameters");
    ownEmitters_ = gpu::createBuffer(ctx, 16 * sizeof(shared::FluidEmitter),
                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload,
                                     "fluid emitters");
    emitterBuffer_ = ownEmitters_.get();
    emitterBufferSize_ = ownEmitters_.size;
    // Bound by every stage that reads the solids (binding 15) until solids come.
    noSolidCells_ = gpu::createBuffer(ctx, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                      gpu::MemoryUsage::DeviceLocal, "fluid no solid cells");
    // Bound at binding 21 (a block list) where no list is walked.
    noSolidList_ = gpu::createBuffer(
        ctx, std::min<VkDeviceSize>(kSolidListBytes, ctx.limits().maxUniformBufferRange),
        VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryUsage::DeviceLocal, "fluid no solid list");
    splatRegions_ =
        gpu::createBuffer(ctx, 4 * sizeof(shared::SplatRegion),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                          gpu::MemoryUsage::DeviceLocal, "fluid splat regions");
    writeParameters();
}

void SmokeSolver::setState(const FieldState& state) {
    fields_.upload(ctx_, state);
}

FieldState SmokeSolver::state() {
    return fields_.download(ctx_, options_.grid);
}

Status SmokeSolver::setEmitters(std::span<const shared::FluidEmitter> emitters) {
    if (Status valid = validateEmitters(emitters); !valid) return valid;
    const VkDeviceSize bytes = emitters.size_bytes();
    if (bytes > ownEmitters_.size) {
        ownEmitters_ = gpu::createBuffer(ctx_, std::max<VkDeviceSize>(bytes, 2 * ownEmitters_.size),
                                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         gpu::MemoryUsage::Upload, "fluid emitters");
    }
    if (bytes > 0) std::memcpy(ownEmitters_.mapped, emitters.data(), bytes);
    setEmitterBuffer(ownEmitters_, uint32_t(emitters.size()));
    return Ok{};
}

void SmokeSolver::setEmitterBuffer(const gpu::Buffer& buffer, uint32_t count) {
    emitterBuffer_ = buffer.get();
    emitterBufferSize_ = buffer.size;
    emitterCount_ = std::min<uint32_t>(count, uint32_t(buffer.size / sizeof(shared::FluidEmitter)));
}

Status SmokeSolver::setSolids(std::span<const shared::FluidSolid> solids) {
    if (Status valid = validateGpuSolids(solids, ctx_.limits().maxUniformBufferRange); !valid)
        return valid;
    if (Status ok = validateSolidOptions(options_); !solids.empty() && !ok) return ok;
    // Made once, at their largest, and never replaced: a recording in flight (several steps
    // recorded together, solids set between them) may name them.
    if (!solids.empty() && solidsBuffer_.get() == VK_NULL_HANDLE) {
        // Storage the GPU fills (vkCmdUpdateBuffer, vkCmdFillBuffer) and reads.
        auto make = [&](uint64_t bytes, const char* name) {
            return gpu::createBuffer(
                ctx_, bytes,
                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT |
                    VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                gpu::MemoryUsage::DeviceLocal, name);
        };
        const GridShape& g = options_.grid;
        // mark_solids.comp's two uniform buffers: the solids and its first pass's box blocks.
        solidsBuffer_ = make(kSolidUniformBytes, "fluid solids");
        solidBoxBlocks_ = make(kSolidUniformBytes, "fluid solid box blocks");
        // A flag byte per cell, rows padded to whole words of four (fluid_solids.glsl).
        const uint64_t flagBytes = uint64_t((g.cellsX + 3) / 4) * g.cellsY * g.cellsZ * 4;
        solidCells_ = make(flagBytes, "fluid solid cells");
        // A byte per cell likewise: its trilinear stencil's solid corners.
        solidCorners_ = make(flagBytes, "fluid solid corners");
        solidHolders_ = make(g.cellCount() * sizeof(uint32_t), "fluid solid holders");
        // A bit per cell, rows padded to whole words of 32 (mark_solids.comp).
        solidBits_ = make(uint64_t((g.cellsX + 31) / 32) * g.cellsY * g.cellsZ * sizeof(uint32_t),
                          "fluid solid bits");
        // One word per Jacobi brick, then its two lists, their dispatches and lengths
        // (solve_pressure.comp).
        solidBricks_ =
            make((3 * uint64_t(solidBrickCount()) + 8) * sizeof(uint32_t), "fluid solid bricks");
        // One word per workgroup-sized block of the largest dispatch (cells + 1 along each axis),
        // then the block lists and their dispatches (fluid_solids.glsl).
        solidBlocks_ = make((uint64_t(solidBlockCount()) + 3 * kSolidBlockLists) * sizeof(uint32_t),
                            "fluid solid blocks");
        solidLists_ = make(kSolidBlockLists * kSolidListBytes, "fluid solid block lists");
        if (splitSolids_) uploadEmptySolidLists();
    }
    solids_.assign(solids.begin(), solids.end());
    programs_.setSolids(!solids_.empty());
    return Ok{};
}

glm::uvec3 SmokeSolver::solidBlockGrid() const {
    const std::array<uint32_t, 3>& w = options_.workgroup;
    const glm::uvec3 size(w[0], w[1], w[2]);
    return (fields_.cells + 1u + size - 1u) / size;
}

glm::uvec3 SmokeSolver::solidBrickGrid() const {
    const glm::uvec3 brick(kPressureBrickX, kPressureRows, kPressureLayers);
    return (fields_.cells + brick - 1u) / brick;
}

uint32_t SmokeSolver::solidBlockCount() const {
    const glm::uvec3 g = solidBlockGrid();
    return g.x * g.y * g.z;
}

uint32_t SmokeSolver::solidBrickCount() const {
    const glm::uvec3 g = solidBrickGrid();
    return g.x * g.y * g.z;
}

namespace {

// A block list's entry and a brick list's: the coordinates packed as fluid_solids.glsl's
// packSolidBlock and solve_pressure.comp unpack them.
uint32_t packSolidBlock(glm::uvec3 block) {
    return block.x | block.y << 11 | block.z << 22;
}
uint32_t packSolidBrick(glm::uvec3 brick) {
    return brick.x | brick.y << 10 | brick.z << 20;
}

// The extents a split stage dispatches over (fluid_solids.glsl's block lists (L - 1) / 2).
std::array<glm::uvec3, 5> splitExtents(glm::uvec3 cells) {
    return {cells, cells + glm::uvec3(1, 0, 0), cells + glm::uvec3(0, 1, 0),
            cells + glm::uvec3(0, 0, 1), cells + glm::uvec3(1)};
}

} // namespace

void SmokeSolver::uploadEmptySolidLists() {
    const std::array<uint32_t, 3>& w = options_.workgroup;
    const glm::uvec3 size(w[0], w[1], w[2]);
    const glm::uvec3 blocks = solidBlockGrid();
    const uint32_t total = solidBlockCount();
    std::vector<uint32_t> words(size_t(total) + 3 * kSolidBlockLists, 0);
    std::vector<uint32_t> lists(size_t(kSolidBlockLists) * kSolidListEntries, 0);
    const std::array<glm::uvec3, 5> extents = splitExtents(fields_.cells);
    for (uint32_t extent = 0; extent < 5; ++extent) {
        const uint32_t away = 2 * extent + 2; // every block is away from solids
        uint32_t length = 0;
        for (uint32_t i = 0; i < total; ++i) {
            const glm::uvec3 block(i % blocks.x, (i / blocks.x) % blocks.y,
                                   i / (blocks.x * blocks.y));
            if (glm::all(glm::lessThan(block * size, extents[extent])))
                lists[size_t(kSolidListEntries) * (away - 1) + length++] = packSolidBlock(block);
        }
        const size_t near = size_t(total) + 3 * (away - 2);
        words[near + 0] = 0, words[near + 1] = 1, words[near + 2] = 1;
        words[near + 3] = length, words[near + 4] = 1, words[near + 5] = 1;
    }
    gpu::uploadBuffer(ctx_, solidBlocks_, std::span<const uint32_t>(words));
    gpu::uploadBuffer(ctx_, solidLists_, std::span<const uint32_t>(lists));
    const uint32_t bricks = solidBrickCount(), group = w[0] * w[1] * w[2];
    std::vector<uint32_t> brickWords(3 * size_t(bricks) + 8, 0);
    const glm::uvec3 brickGrid = solidBrickGrid();
    for (uint32_t i = 0; i < bricks; ++i) // the far list
        brickWords[2 * size_t(bricks) + i] = packSolidBrick(
            {i % brickGrid.x, (i / brickGrid.x) % brickGrid.y, i / (brickGrid.x * brickGrid.y)});
    const size_t args = 3 * size_t(bricks);
    brickWords[args + 1] = brickWords[args + 2] = 1;     // near: no group
    brickWords[args + 3] = (bricks + group - 1) / group; // far: every brick
    brickWords[args + 4] = brickWords[args + 5] = 1;
    brickWords[args + 7] = bricks;
    gpu::uploadBuffer(ctx_, solidBricks_, std::span<const uint32_t>(brickWords));
}

void SmokeSolver::writeParameters() {
    const shared::FluidParameters parameters = makeParameters(options_, emitterCount_, time_);
    std::memcpy(parameters_.mapped, &parameters, sizeof(parameters));
}

SmokeSolver::Writes SmokeSolver::withSolidBindings(std::span<const gpu::DescriptorWrite> writes,
                                                   const gpu::Program& program,
                                                   uint32_t list) const {
    Writes all(writes.begin(), writes.end());
    auto written = [&](uint32_t binding) {
        return std::any_of(writes.begin(), writes.end(),
                           [&](const gpu::DescriptorWrite& w) { return w.binding == binding; });
    };
    auto orNone = [&](const gpu::Buffer& buffer) -> const gpu::Buffer& {
        return buffer.get() != VK_NULL_HANDLE ? buffer : noSolidCells_;
    };
    for (const gpu::BindingDesc& b : program.bindings()) {
        if (b.binding == 15 && !written(15))
            all.push_back(gpu::bindBuffer(15, orNone(solidCells_)));
        if (b.binding == 19 && !written(19))
            all.push_back(gpu::bindBuffer(19, orNone(solidBlocks_)));
        if (b.binding == 21 && !written(21))
            all.push_back(list == 0 ? gpu::bindBuffer(21, noSolidList_)
                                    : gpu::bindBuffer(21, solidLists_, (list - 1) * kSolidListBytes,
                                                      kSolidListBytes));
        if (b.binding == 22 && !written(22))
            all.push_back(gpu::bindBuffer(22, orNone(solidCorners_)));
    }
    return all;
}

void SmokeSolver::dispatch(VkCommandBuffer cmd, gpu::Program& program,
                           std::span<const gpu::DescriptorWrite> writes, glm::uvec3 extent) const {
    program.bind(cmd, withSolidBindings(writes, program, 0));
    program.push(cmd, shared::FluidDispatch{0, 0, 0, 0});
    ++dispatches_;
    const std::array<uint32_t, 3>& group = options_.workgroup;
    vkCmdDispatch(cmd, gpu::groupCount(extent.x, group[0]), gpu::groupCount(extent.y, group[1]),
                  gpu::groupCount(extent.z, group[2]));
}

void SmokeSolver::dispatchStage(VkCommandBuffer cmd, const StageProgram& p,
                                std::span<const gpu::DescriptorWrite> writes, glm::uvec3 extent) {
    if (!splitSolids_ || solids_.empty()) {
        dispatch(cmd, programs_.get(p.name, p.target, p.variant, p.direct), writes, extent);
        return;
    }
    const std::array<glm::uvec3, 5> extents = splitExtents(fields_.cells);
    uint32_t kind = 0;
    while (kind < 5 && extents[kind] != extent)
        ++kind;
    if (kind == 5)
        throw std::logic_error("stage " + std::string(p.name) +
                               ": no block list covers its dispatch");
    const VkDeviceSize dispatches = VkDeviceSize(solidBlockCount()) * sizeof(uint32_t);
    // Away from solids, then near them. The two write disjoint blocks of what one dispatch
    // writes; the barrier between them only tells the validation layer so.
    for (uint32_t list : {2 * kind + 2, 2 * kind + 1}) {
        if (list % 2 == 1) fieldBarrier(cmd);
        gpu::Program& program = programs_.get(p.name, p.target, p.variant, p.direct, list);
        program.bind(cmd, withSolidBindings(writes, program, list));
        program.push(cmd, shared::FluidDispatch{0, 0, 0, 0});
        ++dispatches_;
        vkCmdDispatchIndirect(cmd, solidBlocks_.get(),
                              dispatches + 3 * (list - 1) * sizeof(uint32_t));
    }
}

void SmokeSolver::storeFields(
    VkCommandBuffer cmd, bool direct,
    std::initializer_list<std::pair<const gpu::Buffer*, gpu::Image*>> fields) {
    if (direct) { // the dispatches stored into the images themselves
        fieldBarrier(cmd);
        return;
    }
    // A copy cannot convert: binary16 images are stored into by store_half instead.
    std::vector<std::pair<const gpu::Buffer*, gpu::Image*>> copies, converted;
    for (const auto& pair : fields)
        (isHalf(pair.second->format) ? converted : copies).push_back(pair);
    if (!converted.empty()) {
        fieldBarrier(cmd);
        for (const auto& [buffer, image] : converted) {
            const bool rgba = image->format == VK_FORMAT_R16G16B16A16_SFLOAT;
            const gpu::DescriptorWrite writes[] = {gpu::bindBuffer(1, *buffer), storage(2, *image)};
            dispatch(cmd, programs_.get(rgba ? "store_half_rgba" : "store_half"), writes,
                     glm::uvec3(image->extent.width, image->extent.height, image->extent.depth));
        }
        fieldBarrier(cmd);
    }
    if (copies.empty()) return;
    // The dispatches that wrote the buffers → the copies, each image in TRANSFER_DST_OPTIMAL (its
    // contents are replaced whole) → every later command, the images back in GENERAL.
    std::vector<VkImage> images;
    for (const auto& copy : copies)
        images.push_back(copy.second->get());
    const VkPipelineStageFlags2 all =
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    const VkAccessFlags2 everything =
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
        VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;
    gpu::imageBarriers(cmd, images, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       all, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       all, everything);
    for (const auto& [buffer, image] : copies) {
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = image->extent;
        vkCmdCopyBufferToImage(cmd, buffer->get(), image->get(),
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    }
    gpu::imageBarriers(cmd, images, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
                       all, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       all, everything);
}

SmokeSolver::Writes SmokeSolver::withVelocity(int set) const {
    const auto& v = fields_.velocity[size_t(set)];
    return {gpu::bindBuffer(0, parameters_), storage(1, v[0]), storage(2, v[1]), storage(3, v[2])};
}

// --- Stages -------------------------------------------------------------------------------------

void SmokeSolver::markSolids(VkCommandBuffer cmd) {
    if (solids_.empty()) return;
    // The solids go into the command buffer itself: steps recorded one after another into one
    // command buffer (a frame's steps) each mark their own.
    const VkDeviceSize bytes = solids_.size() * sizeof(shared::FluidSolid);
    vkCmdUpdateBuffer(cmd, solidsBuffer_.get(), 0, bytes, solids_.data());
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_UNIFORM_READ_BIT);
    SmokeFields& f = fields_;
    const auto& v = f.velocity[size_t(f.currentVelocity)];
    // The flags and corners are written through bindings 17 and 9 (passes 1 and 4) and the flags
    // read through 15 (pass 3): never the same buffer at both in one dispatch.
    Writes writes = {
        gpu::bindBuffer(0, parameters_),
        gpu::bindBuffer(1, solidsBuffer_),
        storage(2, v[0]),
        storage(3, v[1]),
        storage(4, v[2]),
        storage(5, f.pigment[size_t(f.currentPigment)]),
        gpu::bindBuffer(6, solidBoxBlocks_),
        gpu::bindBuffer(7, splitSolids_ ? solidLists_ : noSolidCells_),
        gpu::bindBuffer(8, solidBits_),
        gpu::bindBuffer(9, solidCorners_),
        gpu::bindBuffer(15, noSolidCells_),
        gpu::bindBuffer(16, solidHolders_),
        gpu::bindBuffer(17, solidCells_),
        gpu::bindBuffer(18, solidBricks_),
        gpu::bindBuffer(19, noSolidCells_),
        gpu::bindBuffer(20, solidBlocks_),
        gpu::bindBuffer(22, noSolidCells_), // written at 9
    };
    // Every cell air and without flags, then the solids' boxes, then the flags over the solids'
    // joint box two cells wider (a flag's neighbour and stencil bits reach a cell beyond; the
    // whole axis where it is periodic: they wrap), the lists, the faces and pigment.
    const uint32_t blockCount = solidBlockCount(), brickCount = solidBrickCount();
    vkCmdFillBuffer(cmd, solidHolders_.get(), 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(cmd, solidCells_.get(), 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(cmd, solidCorners_.get(), 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(cmd, solidBricks_.get(), 0, brickCount * sizeof(uint32_t), 0);
    vkCmdFillBuffer(cmd, solidBlocks_.get(), 0, blockCount * sizeof(uint32_t), 0);
    vkCmdFillBuffer(cmd, solidBits_.get(), 0, VK_WHOLE_SIZE, 0);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    // Each solid's bounding box (one cell wider: the box is found in fp32) in workgroup-sized
    // blocks of the grid, pass 0's entries, 4,096 a dispatch.
    const float h = options_.grid.cellSize;
    const glm::ivec3 last = glm::ivec3(f.cells) - 1;
    const std::array<uint32_t, 3>& group = options_.workgroup;
    const glm::ivec3 size(group[0], group[1], group[2]);
    glm::ivec3 jointLow = last + 1, jointHigh(-1);
    std::vector<glm::uvec4> boxBlocks;
    for (size_t i = 0; i < solids_.size(); ++i) {
        const shared::FluidSolid& s = solids_[i];
        const glm::vec3 a(s.endA), b(s.endB);
        const float r = s.endA.w;
        const glm::ivec3 low =
            glm::max(glm::ivec3(glm::floor((glm::min(a, b) - r) / h - 0.5f)) - 1, glm::ivec3(0));
        const glm::ivec3 high =
            glm::min(glm::ivec3(glm::ceil((glm::max(a, b) + r) / h - 0.5f)) + 1, last);
        if (glm::any(glm::greaterThan(low, high))) continue; // wholly outside the grid
        jointLow = glm::min(jointLow, low);
        jointHigh = glm::max(jointHigh, high);
        // The box's blocks, less those none of whose cell centres can lie within the radius of
        // the axis: the distance from the centres' bounding sphere to the axis beyond the radius
        // by a cell (far beyond fp32's error), which leaves out most of the box of a limb that
        // lies across it.
        const glm::ivec3 first = low / size, end = high / size;
        const glm::vec3 ab = b - a;
        const float length2 = glm::dot(ab, ab);
        for (int z = first.z; z <= end.z; ++z)
            for (int y = first.y; y <= end.y; ++y)
                for (int x = first.x; x <= end.x; ++x) {
                    const glm::ivec3 block(x, y, z);
                    const glm::vec3 lo = (glm::vec3(block * size) + 0.5f) * h;
                    const glm::vec3 hi =
                        (glm::vec3(glm::min(block * size + size - 1, last)) + 0.5f) * h;
                    const glm::vec3 centre = 0.5f * (lo + hi);
                    const float t = length2 > 0.0f
                                        ? glm::clamp(glm::dot(centre - a, ab) / length2, 0.0f, 1.0f)
                                        : 0.0f;
                    const float distance = glm::length(centre - (a + t * ab));
                    if (distance > r + 0.5f * glm::length(hi - lo) + h) continue;
                    boxBlocks.emplace_back(uint32_t(i), uint32_t(x), uint32_t(y), uint32_t(z));
                }
    }
    gpu::Program& cells = programs_.get("mark_solids", 0, 0);
    for (size_t done = 0; done < boxBlocks.size(); done += kBoxBlocksAPass) {
        const size_t count = std::min<size_t>(kBoxBlocksAPass, boxBlocks.size() - done);
        if (done > 0) // the last dispatch has read the entries this update replaces
            gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_NONE,
                               VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_NONE);
        vkCmdUpdateBuffer(cmd, solidBoxBlocks_.get(), 0, count * sizeof(glm::uvec4),
                          boxBlocks.data() + done);
        gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                           VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                           VK_ACCESS_2_UNIFORM_READ_BIT);
        cells.bind(cmd, withSolidBindings(writes, cells, 0));
        cells.push(cmd, shared::FluidDispatch{0, 0, 0, 0});
        ++dispatches_;
        vkCmdDispatch(cmd, uint32_t(count), 1, 1);
    }
    fieldBarrier(cmd);
    if (glm::any(glm::greaterThan(jointLow, jointHigh))) { // no solid in the grid
        if (splitSolids_) makeSolidLists(cmd, writes);
        return;
    }
    for (int axis = 0; axis < 3; ++axis) {
        jointLow[axis] = options_.periodic(axis) ? 0 : std::max(jointLow[axis] - 2, 0);
        jointHigh[axis] =
            options_.periodic(axis) ? last[axis] : std::min(jointHigh[axis] + 2, last[axis]);
    }
    // Over the box's flag words (four cells along x each; the origin in words along x).
    const glm::ivec3 firstWord(jointLow.x / 4, jointLow.y, jointLow.z);
    const glm::uvec3 words(uint32_t(jointHigh.x / 4 - firstWord.x + 1),
                           uint32_t(jointHigh.y - jointLow.y + 1),
                           uint32_t(jointHigh.z - jointLow.z + 1));
    gpu::Program& flags = programs_.get("mark_solids", 0, splitSolids_ ? 4 : 1);
    flags.bind(cmd, withSolidBindings(writes, flags, 0));
    flags.push(cmd, shared::FluidDispatch{0, uint32_t(firstWord.x), uint32_t(firstWord.y),
                                          uint32_t(firstWord.z)});
    ++dispatches_;
    vkCmdDispatch(cmd, gpu::groupCount(words.x, group[0]), gpu::groupCount(words.y, group[1]),
                  gpu::groupCount(words.z, group[2]));
    fieldBarrier(cmd);
    if (splitSolids_) makeSolidLists(cmd, writes);
    // Over the box's cells and the faces past them (one more along each axis), or over the
    // blocks near solids of the cells + 1 (block list 9).
    // A write replaced by its binding.
    auto rebind = [&writes](uint32_t binding, const gpu::Buffer& buffer) {
        for (gpu::DescriptorWrite& w : writes)
            if (w.binding == binding) w = gpu::bindBuffer(binding, buffer);
    };
    rebind(15, solidCells_);
    rebind(17, noSolidCells_);
    rebind(9, noSolidCells_);
    if (splitSolids_) {
        rebind(7, noSolidCells_);  // the block lists stay as pass 2 left them: read at 21
        rebind(18, noSolidCells_); // and the brick lists
        rebind(19, solidBlocks_);
        rebind(20, noSolidCells_);
        const uint32_t list = 2 * 4 + 1;
        gpu::Program& faces = programs_.get("mark_solids", 0, 3, false, list);
        faces.bind(cmd, withSolidBindings(writes, faces, list));
        faces.push(cmd, shared::FluidDispatch{0, 0, 0, 0});
        ++dispatches_;
        vkCmdDispatchIndirect(cmd, solidBlocks_.get(),
                              (VkDeviceSize(blockCount) + 3 * (list - 1)) * sizeof(uint32_t));
    } else {
        gpu::Program& faces = programs_.get("mark_solids", 0, 3);
        faces.bind(cmd, withSolidBindings(writes, faces, 0));
        faces.push(cmd, shared::FluidDispatch{0, uint32_t(jointLow.x), uint32_t(jointLow.y),
                                              uint32_t(jointLow.z)});
        ++dispatches_;
        const glm::uvec3 extent(jointHigh - jointLow + 2);
        vkCmdDispatch(cmd, gpu::groupCount(extent.x, group[0]), gpu::groupCount(extent.y, group[1]),
                      gpu::groupCount(extent.z, group[2]));
    }
    fieldBarrier(cmd);
}

void SmokeSolver::makeSolidLists(VkCommandBuffer cmd,
                                 std::span<const gpu::DescriptorWrite> writes) {
    // Pass 2: each block's word (pass 4 marked the bricks'); pass 5: the lists.
    const std::array<uint32_t, 3>& group = options_.workgroup;
    const uint32_t items = solidBlockCount();
    gpu::Program& words = programs_.get("mark_solids", 0, 2);
    words.bind(cmd, withSolidBindings(writes, words, 0));
    words.push(cmd, shared::FluidDispatch{0, 0, 0, 0});
    ++dispatches_;
    vkCmdDispatch(cmd, gpu::groupCount(items, group[0] * group[1] * group[2]), 1, 1);
    fieldBarrier(cmd);
    gpu::Program& lists = programs_.get("mark_solids", 0, 5);
    lists.bind(cmd, withSolidBindings(writes, lists, 0));
    lists.push(cmd, shared::FluidDispatch{0, 0, 0, 0});
    ++dispatches_;
    vkCmdDispatch(cmd, 1, 1, 1);
    // The lists are read by the stages' indirect dispatches and their workgroups.
    gpu::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
        VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
        VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
            VK_ACCESS_2_UNIFORM_READ_BIT);
}

void SmokeSolver::splatImpulses(VkCommandBuffer cmd) {
    if (emitterCount_ == 0) return;
    SmokeFields& f = fields_;
    gpu::DescriptorWrite emitters;
    emitters.binding = 1;
    emitters.buffer = {emitterBuffer_, 0, emitterBufferSize_};
    // The emitters' bounding box, per target, as indirect dispatches (emitters may be written on
    // the GPU, so only the GPU knows where they are).
    programs_.get("emitter_bounds")
        .bind(cmd, {gpu::bindBuffer(0, parameters_), emitters, gpu::bindBuffer(2, splatRegions_)});
    ++dispatches_;
    vkCmdDispatch(cmd, 1, 1, 1);
    gpu::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
        VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
        VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    const auto& v = f.velocity[size_t(f.currentVelocity)];
    const gpu::DescriptorWrite writes[] = {
        gpu::bindBuffer(0, parameters_),
        emitters,
        storage(2, v[0]),
        storage(3, v[1]),
        storage(4, v[2]),
        storage(5, f.pigment[size_t(f.currentPigment)]),
        gpu::bindBuffer(6, splatRegions_),
    };
    for (uint32_t target = 0; target < 4; ++target) {
        gpu::Program& prog = programs_.get("splat_impulses", target);
        prog.bind(cmd, withSolidBindings(writes, prog, 0));
        prog.push(cmd, shared::FluidDispatch{0, 0, 0, 0});
        ++dispatches_;
        vkCmdDispatchIndirect(cmd, splatRegions_.get(), target * sizeof(shared::SplatRegion));
    }
    fieldBarrier(cmd);
}

// The advection passes of options().advection (shaders/shared/fluid.h, MFX_ADVECT_*): each
// writes the next field's image set (`to`), the work field of the pass after it; the last pass
// leaves the advected field there.
std::vector<uint32_t> SmokeSolver::advectionPasses() const {
    switch (options_.advection) {
    case AdvectionScheme::SemiLagrangian:
        break;
    case AdvectionScheme::MacCormack:
        return {MFX_ADVECT_PREDICT, MFX_ADVECT_MACCORMACK_CORRECT};
    case AdvectionScheme::Bfecc:
        return {MFX_ADVECT_PREDICT, MFX_ADVECT_BFECC_COMPENSATE, MFX_ADVECT_BFECC_FINAL};
    }
    return {MFX_ADVECT_SEMI_LAGRANGIAN};
}

void SmokeSolver::advectVelocity(VkCommandBuffer cmd) {
    SmokeFields& f = fields_;
    const int from = f.currentVelocity, to = 1 - f.currentVelocity;
    auto& out = f.velocity[size_t(to)];
    // A pass after the first reads the previous pass's result where it writes: those go through
    // the buffers.
    const std::vector<uint32_t> passes = advectionPasses();
    const bool direct = direct_ && passes.size() == 1;
    for (uint32_t pass : passes) {
        for (uint32_t c = 0; c < 3; ++c) {
            Writes w = withVelocity(from);
            w.push_back(gpu::bindBuffer(4, f.scratch[c]));
            w.push_back(storage(5, out[c]));
            w.push_back(storage(6, out[c]));
            dispatchStage(cmd, {"advect_velocity", c, pass, direct}, w,
                          faceExtent(options_.grid, int(c)));
        }
        storeFields(cmd, direct,
                    {{&f.scratch[0], &out[0]}, {&f.scratch[1], &out[1]}, {&f.scratch[2], &out[2]}});
    }
    f.currentVelocity = to;
}

void SmokeSolver::advectPigment(VkCommandBuffer cmd) {
    SmokeFields& f = fields_;
    const int from = f.currentPigment, to = 1 - f.currentPigment;
    const std::vector<uint32_t> passes = advectionPasses();
    const bool direct = direct_ && passes.size() == 1; // as advectVelocity
    for (uint32_t pass : passes) {
        Writes w = withVelocity(f.currentVelocity);
        w.push_back(storage(4, f.pigment[size_t(from)]));
        w.push_back(gpu::bindBuffer(5, f.scratch[0]));
        w.push_back(storage(6, f.pigment[size_t(to)]));
        w.push_back(storage(7, f.pigment[size_t(to)]));
        dispatchStage(cmd, {"advect_pigment", MFX_TARGET_PIGMENT, pass, direct}, w, f.cells);
        storeFields(cmd, direct, {{&f.scratch[0], &f.pigment[size_t(to)]}});
    }
    f.currentPigment = to;
}

void SmokeSolver::applyBuoyancy(VkCommandBuffer cmd) {
    if (options_.buoyancy == 0.0f) return;
    SmokeFields& f = fields_;
    gpu::Image& velocityY = f.velocity[size_t(f.currentVelocity)][1];
    const gpu::DescriptorWrite writes[] = {gpu::bindBuffer(0, parameters_), storage(1, velocityY),
                                           storage(2, f.pigment[size_t(f.currentPigment)]),
                                           gpu::bindBuffer(3, f.scratch[1]), storage(4, velocityY)};
    dispatchStage(cmd, {"apply_buoyancy", MFX_TARGET_VELOCITY_Y, 0, direct_}, writes,
                  faceExtent(options_.grid, 1));
    storeFields(cmd, direct_, {{&f.scratch[1], &velocityY}});
}

void SmokeSolver::applyTurbulence(VkCommandBuffer cmd) {
    if (options_.turbulence == 0.0f) return;
    SmokeFields& f = fields_;
    auto& v = f.velocity[size_t(f.currentVelocity)];
    // The potential on every edge once, then each component's faces from it.
    const glm::uvec3 corners = f.cells + glm::uvec3(1);
    const VkDeviceSize bytes = VkDeviceSize(corners.x) * corners.y * corners.z * sizeof(glm::vec4);
    if (turbulencePotential_.size < bytes)
        turbulencePotential_ =
            gpu::createBuffer(ctx_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              gpu::MemoryUsage::DeviceLocal, "turbulence potential");
    const gpu::DescriptorWrite potential[] = {gpu::bindBuffer(0, parameters_),
                                              gpu::bindBuffer(1, turbulencePotential_)};
    dispatch(cmd, programs_.get("turbulence_potential"), potential, corners);
    fieldBarrier(cmd);
    for (uint32_t c = 0; c < 3; ++c) {
        const gpu::DescriptorWrite writes[] = {gpu::bindBuffer(0, parameters_), storage(1, v[c]),
                                               gpu::bindBuffer(2, f.scratch[c]), storage(3, v[c]),
                                               gpu::bindBuffer(4, turbulencePotential_)};
        dispatchStage(cmd, {"apply_turbulence", c, 0, direct_}, writes,
                      faceExtent(options_.grid, int(c)));
    }
    storeFields(cmd, direct_,
                {{&f.scratch[0], &v[0]}, {&f.scratch[1], &v[1]}, {&f.scratch[2], &v[2]}});
}

void SmokeSolver::vorticityConfinement(VkCommandBuffer cmd) {
    if (options_.vorticity == 0.0f) return;
    // Vorticity per cell, then the confinement force per cell, then the faces. On the direct
    // path the first two are one dispatch (vorticity_force.comp: the vorticity of a block and its
    // ring in shared memory), where the workgroup's tile fits the device's shared memory.
    SmokeFields& f = fields_;
    if (fusedVorticity_) {
        Writes fused = withVelocity(f.currentVelocity);
        fused.push_back(storage(4, f.force));
        dispatch(cmd, programs_.get("vorticity_force", 0, 0, true), fused, f.cells);
        fieldBarrier(cmd);
        applyVorticityForce(cmd);
        return;
    }
    Writes vorticity = withVelocity(f.currentVelocity);
    vorticity.push_back(gpu::bindBuffer(4, f.scratch[0]));
    vorticity.push_back(storage(5, f.vorticity));
    dispatch(cmd, programs_.get("compute_vorticity", 0, 0, direct_), vorticity, f.cells);
    storeFields(cmd, direct_, {{&f.scratch[0], &f.vorticity}});

    const gpu::DescriptorWrite force[] = {gpu::bindBuffer(0, parameters_), storage(1, f.vorticity),
                                          gpu::bindBuffer(2, f.scratch[0]), storage(3, f.force)};
    dispatch(cmd, programs_.get("confinement_force", 0, 0, direct_), force, f.cells);
    storeFields(cmd, direct_, {{&f.scratch[0], &f.force}});
    applyVorticityForce(cmd);
}

void SmokeSolver::applyVorticityForce(VkCommandBuffer cmd) {
    SmokeFields& f = fields_;
    auto& v = f.velocity[size_t(f.currentVelocity)];
    Writes apply = withVelocity(f.currentVelocity);
    apply.push_back(storage(4, f.force));
    for (uint32_t c = 0; c < 3; ++c)
        apply.push_back(gpu::bindBuffer(5 + c, f.scratch[c]));
    for (uint32_t c = 0; c < 3; ++c)
        apply.push_back(storage(8 + c, v[c]));
    dispatchStage(cmd, {"apply_vorticity_force", 0, 0, direct_}, apply, f.cells + glm::uvec3(1));
    storeFields(cmd, direct_,
                {{&f.scratch[0], &v[0]}, {&f.scratch[1], &v[1]}, {&f.scratch[2], &v[2]}});
}

void SmokeSolver::diffuseViscosity(VkCommandBuffer cmd) {
    const uint32_t sweeps = options_.viscosityIterations;
    if (options_.viscosity == 0.0f || sweeps == 0) return;
    SmokeFields& f = fields_;
    const int source = f.currentVelocity, other = 1 - f.currentVelocity, scratch = 2;
    // Alternate between `other` and the scratch set so that the last sweep lands in `other`.
    int in = source;
    int out = sweeps % 2 == 1 ? other : scratch;
    for (uint32_t sweep = 0; sweep < sweeps; ++sweep) {
        Writes w = withVelocity(source);
        for (uint32_t c = 0; c < 3; ++c)
            w.push_back(storage(4 + c, f.velocity[size_t(in)][c]));
        for (uint32_t c = 0; c < 3; ++c)
            w.push_back(storage(7 + c, f.velocity[size_t(out)][c]));
        for (uint32_t c = 0; c < 3; ++c)
            dispatchStage(cmd, {"diffuse_viscosity", c}, w, faceExtent(options_.grid, int(c)));
        fieldBarrier(cmd);
        in = out;
        out = out == other ? scratch : other;
    }
    f.currentVelocity = other;
}

void SmokeSolver::applyBoundaries(VkCommandBuffer cmd) {
    const Writes w = withVelocity(fields_.currentVelocity);
    for (uint32_t c = 0; c < 3; ++c) {
        glm::uvec3 layers = faceExtent(options_.grid, int(c));
        layers[int(c)] = 2; // only the two boundary layers of faces normal to c
        dispatch(cmd, programs_.get("apply_boundaries", c), w, layers);
    }
    fieldBarrier(cmd);
}

void SmokeSolver::computeDivergence(VkCommandBuffer cmd) {
    SmokeFields& f = fields_;
    // In a step, a cold Jacobi solve's first sweep (shaders/fluid/compute_divergence.comp):
    // packed where the solve keeps pressure packed until its last sweep, else into the image the
    // first sweep writes.
    const bool packed = f.packedSolve && options_.jacobiIterations > 1;
    const uint32_t firstSweep = stepping_ && options_.firstSweepFused() ? (packed ? 1u : 2u) : 0u;
    Writes w = withVelocity(f.currentVelocity);
    w.push_back(gpu::bindBuffer(4, f.scratch[0]));
    w.push_back(storage(5, f.divergence));
    w.push_back(gpu::bindBuffer(6, f.packedDivergence));
    w.push_back(gpu::bindBuffer(7, f.packedPressure[1]));
    w.push_back(storage(8, f.pressure[size_t(1 - f.currentPressure)]));
    dispatchStage(cmd, {"compute_divergence", 0, firstSweep, direct_}, w, f.cells);
    // Either path's barriers (the copy's carry a global memory barrier) cover the sweep's output.
    storeFields(cmd, direct_, {{&f.scratch[0], &f.divergence}});
    firstSweepDone_ = firstSweep;
}

void SmokeSolver::solvePressure(VkCommandBuffer cmd) {
    SmokeFields& f = fields_;
    if (multigrid_) {
        // The other solvers write the solution x-fastest into a buffer, copied over the live image.
        gpu::Image& pressure = f.pressure[size_t(f.currentPressure)];
        const bool solids = !solids_.empty();
        dispatches_ += multigrid_->record(cmd, f.divergence, pressure, f.scratch[0],
                                          solids ? solidCells_ : noSolidCells_, solids);
        storeFields(cmd, false, {{&f.scratch[0], &pressure}});
        return;
    }
    const uint32_t sweeps = options_.jacobiIterations;
    // A cold start: the first sweep takes its input as 0 (mode bit 2) and reads no pressure; with
    // no sweep at all the pressure is cleared. In a step the divergence pass may have done the
    // first sweep already (packed into packedPressure[1], or into the other image).
    const bool zeroFirst = !options_.warmStart && sweeps > 0;
    const uint32_t firstSweepDone = std::exchange(firstSweepDone_, 0u);
    if (!options_.warmStart && sweeps == 0) {
        const VkClearColorValue zero{};
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, f.pressure[size_t(f.currentPressure)].get(),
                             VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
        fieldBarrier(cmd);
    }
    // Bricks of 4 x kPressureRows x kPressureLayers cells. Between the first and the last sweep
    // pressure and divergence live packed (shaders/fluid/solve_pressure.comp): the first sweep
    // reads the live r32f image, the last writes the other one.
    const glm::uvec3 bricks((f.cells.x + kPressureBrickX - 1) / kPressureBrickX,
                            (f.cells.y + kPressureRows - 1) / kPressureRows,
                            (f.cells.z + kPressureLayers - 1) / kPressureLayers);
    size_t packedIn = 0;
    if (firstSweepDone == 1) packedIn = 1;                              // packed
    if (firstSweepDone == 2) f.currentPressure = 1 - f.currentPressure; // the other image
    for (uint32_t sweep = firstSweepDone != 0 ? 1u : 0u; sweep < sweeps; ++sweep) {
        const bool first = sweep == 0, last = sweep + 1 == sweeps;
        const uint32_t mode = (f.packedSolve ? (first ? 0u : 1u) | (last ? 0u : 2u) : 0u) |
                              (first && zeroFirst ? 4u : 0u);
        const size_t in = size_t(f.currentPressure), out = 1 - in, packedOut = 1 - packedIn;
        const gpu::DescriptorWrite writes[] = {
            gpu::bindBuffer(0, parameters_),
            storage(1, f.divergence),
            storage(2, f.pressure[in]),
            storage(3, f.pressure[out]),
            gpu::bindBuffer(4, f.packedDivergence),
            gpu::bindBuffer(5, f.packedPressure[packedIn]),
            gpu::bindBuffer(6, f.packedPressure[packedOut]),
            gpu::bindBuffer(7, f.packedPressure[packedIn]),
            gpu::bindBuffer(8, solidBricks_.get() != VK_NULL_HANDLE ? solidBricks_ : noSolidCells_),
        };
        if (splitSolids_ && !solids_.empty()) {
            // The bricks away from solids, then those near them (solve_pressure.comp's lists).
            const VkDeviceSize lists = 3 * VkDeviceSize(solidBrickCount()) * sizeof(uint32_t);
            for (uint32_t list : {2u, 1u}) {
                if (list == 1u) fieldBarrier(cmd); // as dispatchStage's
                gpu::Program& program = programs_.get("solve_pressure", 0, mode, false, list);
                program.bind(cmd, withSolidBindings(writes, program, 0));
                program.push(cmd, shared::FluidDispatch{0, 0, 0, 0});
                ++dispatches_;
                vkCmdDispatchIndirect(cmd, solidBricks_.get(),
                                      lists + 3 * (list - 1) * sizeof(uint32_t));
            }
        } else {
            dispatch(cmd, programs_.get("solve_pressure", 0, mode), writes, bricks);
        }
        fieldBarrier(cmd);
        if (mode & 2u)
            packedIn = packedOut;
        else
            f.currentPressure = int(out); // this sweep wrote the other r32f image
    }
}

void SmokeSolver::project(VkCommandBuffer cmd) {
    SmokeFields& f = fields_;
    auto& v = f.velocity[size_t(f.currentVelocity)];
    for (uint32_t c = 0; c < 3; ++c) {
        const gpu::DescriptorWrite w[] = {gpu::bindBuffer(0, parameters_), storage(1, v[c]),
                                          storage(4, f.pressure[size_t(f.currentPressure)]),
                                          gpu::bindBuffer(5, f.scratch[c]), storage(6, v[c])};
        dispatchStage(cmd, {"project", c, 0, direct_}, w, faceExtent(options_.grid, int(c)));
    }
    storeFields(cmd, direct_,
                {{&f.scratch[0], &v[0]}, {&f.scratch[1], &v[1]}, {&f.scratch[2], &v[2]}});
}

// --- Recording
// ------------------------------------------------------------------------------------

void SmokeSolver::recordStage(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer) {
    writeParameters();
    recordStageOnly(cmd, stage, timer);
}

void SmokeSolver::recordStageOnly(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer) {
    if (timer) timer->begin(cmd, stageName(stage));
    (this->*stageEntry(stage).dense)(cmd);
    if (timer) timer->end(cmd);
}

void SmokeSolver::recordStep(VkCommandBuffer cmd, gpu::GpuTimer* timer) {
    writeParameters(); // once: every sub-step and stage reads the same uniform
    lastStepDispatches_.clear();
    // Reset however the recording ends (a pipeline that cannot be made throws): a stage recorded
    // alone afterwards must neither fuse nor skip its first sweep.
    struct StepScope {
        SmokeSolver& solver;
        explicit StepScope(SmokeSolver& s) : solver(s) {
            solver.stepping_ = true;
            solver.firstSweepDone_ = 0;
        }
        ~StepScope() {
            solver.stepping_ = false;
            solver.firstSweepDone_ = 0;
        }
    } scope(*this);
    for (uint32_t substep = 0; substep < options_.substeps; ++substep)
        for (Stage stage : stepOrder()) {
            const uint32_t before = dispatches_;
            recordStageOnly(cmd, stage, timer);
            countStageDispatches(lastStepDispatches_, stage, dispatches_ - before);
        }
    time_ += double(options_.dt);
}

uint64_t SmokeSolver::memoryBytes() const {
    uint64_t bytes = fields_.memoryBytes() + parameters_.size + ownEmitters_.size +
                     solidsBuffer_.size + solidBoxBlocks_.size + solidCells_.size +
                     solidCorners_.size + solidHolders_.size + solidBits_.size + solidBricks_.size +
                     solidBlocks_.size + solidLists_.size + noSolidCells_.size + noSolidList_.size +
                     turbulencePotential_.size;
    if (multigrid_) bytes += multigrid_->memoryBytes();
    return bytes;
}

uint32_t SmokeSolver::recordMeasureActivity(VkCommandBuffer cmd, const gpu::Buffer& out,
                                            gpu::GpuTimer* timer) {
    if (timer) timer->begin(cmd, "measure_activity");
    vkCmdFillBuffer(cmd, out.get(), 0, 2 * sizeof(uint32_t), 0);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    Writes w = withVelocity(fields_.currentVelocity);
    w.push_back(storage(4, fields_.pigment[size_t(fields_.currentPigment)]));
    w.push_back(gpu::bindBuffer(5, out));
    dispatch(cmd, programs_.get("measure_activity"), w, fields_.cells);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_HOST_READ_BIT);
    if (timer) timer->end(cmd);
    return 1;
}

SolverActivity SmokeSolver::finishFrame(const gpu::Buffer& activity, bool measured, bool,
                                        const SettleRules& rules) {
    SolverActivity a;
    if (!measured) return a;
    a.measured = true;
    uint32_t bits[2];
    std::memcpy(bits, activity.mapped, sizeof bits);
    std::memcpy(&a.largestAlpha, &bits[0], 4);
    std::memcpy(&a.largestSpeed, &bits[1], 4);
    // With solids (a scene's "collide") the body keeps the air moving as long as it moves, and air
    // without pigment shows nothing: the pigment alone decides.
    a.settled = a.largestAlpha < rules.alphaThreshold &&
                (a.largestSpeed < rules.settleSpeed || !solids_.empty());
    return a;
}

PigmentVolume SmokeSolver::pigmentVolume() const {
    PigmentVolume v;
    v.layout = PigmentLayout::Image;
    v.image = &fields_.pigment[size_t(fields_.currentPigment)];
    v.bytes = options_.grid.cellCount() * 4 * (options_.storage == Storage::Float16 ? 2 : 4);
    return v;
}

std::vector<uint8_t> SmokeSolver::storedCells() const {
    return std::vector<uint8_t>(options_.grid.cellCount(), 1);
}

uint32_t SmokeSolver::lastPressureIterations() const {
    return multigrid_ ? multigrid_->lastIterations() : options_.jacobiIterations;
}

void SmokeSolver::step() {
    gpu::submitOneShot(ctx_, [&](VkCommandBuffer cmd) { recordStep(cmd); });
}

void SmokeSolver::runStage(Stage stage) {
    gpu::submitOneShot(ctx_, [&](VkCommandBuffer cmd) { recordStage(cmd, stage); });
}

} // namespace mfx::fluid
