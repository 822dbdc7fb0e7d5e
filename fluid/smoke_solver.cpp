#include "fluid/smoke_solver.h"

#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "shaders/embedded.h"
#include "shaders/shared/fluid.h"

#include <algorithm>
#include <cstring>

namespace mfx::fluid {

// The variant of a stage's shader for the solver's storage: binary16 images with fp16
// (shaders/field_formats.glsl).
#define MFX_FIELD_SHADER(name) (options_.storage == Storage::Float16 ? name##_half : name)

namespace {

// Sampled too: a renderer ray-marches the pigment (in GENERAL layout, as the solver keeps it).
constexpr VkImageUsageFlags kFieldUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
    VK_IMAGE_USAGE_SAMPLED_BIT;
constexpr uint32_t kSetsPerProgram = 16;
// Cells per solve_pressure invocation: 4 along x (fixed by the shader, and the cells per element
// of the packed buffers) by kPressureRows along y by kPressureLayers along z.
constexpr uint32_t kPressureBrickX = 4;
constexpr uint32_t kPressureRows = 4;
constexpr uint32_t kPressureLayers = 4;

gpu::BindingDesc uniformBinding(uint32_t binding) {
    return {binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT};
}
gpu::BindingDesc bufferBinding(uint32_t binding) {
    return {binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT};
}

// A compute program whose binding 0 is the parameters uniform and bindings 1..images are storage
// images (with binding `bufferAt`, if any, and those in `bufferMask` storage buffers instead);
// `extra` gives specialization constants from id 11 on.
gpu::Program makeProgram(const gpu::Context& ctx, const SolverOptions& options, const char* name,
                         std::span<const uint32_t> spirv, uint32_t target, uint32_t bindingCount,
                         uint32_t bufferAt = 0, std::span<const uint32_t> extra = {},
                         uint32_t bufferMask = 0) {
    gpu::ComputeProgramDesc desc;
    desc.name = name;
    desc.spirv = spirv;
    desc.bindings.push_back(uniformBinding(0));
    for (uint32_t b = 1; b < bindingCount; ++b)
        desc.bindings.push_back(b == bufferAt || (bufferMask >> b & 1u) != 0
                                    ? bufferBinding(b)
                                    : gpu::BindingDesc{b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                                       VK_SHADER_STAGE_COMPUTE_BIT});
    desc.pushConstantSize = sizeof(shared::FluidDispatch);
    desc.maxSets = kSetsPerProgram;
    // Constant ids as in shaders/fluid_common.glsl: target, the six boundary kinds, integrator.
    desc.specialization = {target};
    for (const FaceBoundary& face : options.boundaries)
        desc.specialization.push_back(uint32_t(face.kind));
    desc.specialization.push_back(uint32_t(options.integrator));
    for (uint32_t size : options.workgroup) // ids 8-10: the workgroup shape
        desc.specialization.push_back(size);
    desc.specialization.insert(desc.specialization.end(), extra.begin(), extra.end()); // ids 11-
    return gpu::createComputeProgram(ctx, desc);
}

gpu::DescriptorWrite storage(uint32_t binding, const gpu::Image& image) {
    return gpu::bindImage(binding, image, VK_IMAGE_LAYOUT_GENERAL);
}

// The formats of the stored fields (velocity and pressure; pigment) for the options' storage.
VkFormat scalarFormat(const SolverOptions& options) {
    return options.storage == Storage::Float16 ? VK_FORMAT_R16_SFLOAT : VK_FORMAT_R32_SFLOAT;
}
VkFormat rgbaFormat(const SolverOptions& options) {
    return options.storage == Storage::Float16 ? VK_FORMAT_R16G16B16A16_SFLOAT
                                               : VK_FORMAT_R32G32B32A32_SFLOAT;
}

bool isHalf(VkFormat format) {
    return format == VK_FORMAT_R16_SFLOAT || format == VK_FORMAT_R16G16B16A16_SFLOAT;
}

// IEEE 754-2008 binary16 bits of `v`, rounded to nearest with ties to even (the rounding of
// fluid/reference/half_storage.cpp); magnitudes that round above 65504 become infinite.
uint16_t toHalfBits(float v) {
    uint32_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    const uint16_t sign = uint16_t((bits >> 16) & 0x8000u);
    const uint32_t magnitude = bits & 0x7fffffffu;
    if (magnitude >= 0x7f800000u) // infinity, NaN (kept quiet)
        return uint16_t(sign | 0x7c00u | (magnitude > 0x7f800000u ? 0x200u : 0u));
    if (magnitude >= 0x477ff000u) return uint16_t(sign | 0x7c00u); // rounds to >= 65520
    if (magnitude < 0x38800000u) { // below 2^-14: a subnormal half, in units of 2^-24
        const float units = std::nearbyint(std::abs(v) * 16777216.0f); // exact scaling
        return uint16_t(sign | uint16_t(units));
    }
    // Normal: drop 13 fraction bits, rounding to nearest even (a carry may bump the exponent).
    const uint32_t rebased = magnitude - (112u << 23);
    const uint32_t dropped = rebased & 0x1fffu;
    uint32_t half = rebased >> 13;
    if (dropped > 0x1000u || (dropped == 0x1000u && (half & 1u))) ++half;
    return uint16_t(sign | half);
}

float fromHalfBits(uint16_t h) {
    const uint32_t sign = uint32_t(h & 0x8000u) << 16;
    const uint32_t exponent = (h >> 10) & 0x1fu, fraction = h & 0x3ffu;
    if (exponent == 0) { // zero or subnormal
        const float value = float(fraction) / 16777216.0f;
        return sign ? -value : value;
    }
    const uint32_t bits = exponent == 31 ? sign | 0x7f800000u | (fraction << 13)
                                         : sign | ((exponent + 112u) << 23) | (fraction << 13);
    float value = 0.0f;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

} // namespace

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
    : ctx_(ctx), options_(options),
      cells_(options.grid.cellsX, options.grid.cellsY, options.grid.cellsZ) {
    auto makeImage = [&](glm::uvec3 extent, VkFormat format, const char* name) {
        gpu::ImageDesc desc;
        desc.extent = {extent.x, extent.y, extent.z};
        desc.format = format;
        desc.usage = kFieldUsage;
        desc.is3D = true;
        desc.debugName = name;
        return gpu::createImage(ctx, desc);
    };
    for (int set = 0; set < 3; ++set)
        for (int c = 0; c < 3; ++c)
            velocity_[set][c] =
                makeImage(faceExtent(options.grid, c), scalarFormat(options), "velocity");
    for (int i = 0; i < 2; ++i) {
        pigment_[i] = makeImage(cells_, rgbaFormat(options), "pigment");
        pressure_[i] = makeImage(cells_, scalarFormat(options), "pressure");
    }
    divergence_ = makeImage(cells_, VK_FORMAT_R32_SFLOAT, "divergence");
    // Four x-consecutive cells per vec4 (shaders/solve_pressure.comp). A grid too large for one
    // storage buffer solves on the r32f images alone (placeholders fill the unused bindings).
    VkDeviceSize packedBytes = VkDeviceSize((cells_.x + kPressureBrickX - 1) / kPressureBrickX) *
                               cells_.y * cells_.z * 4 * sizeof(float);
    packedSolve_ = packedBytes <= ctx.limits().maxStorageBufferRange;
    if (!packedSolve_) packedBytes = 4 * sizeof(float);
    for (gpu::Buffer& buffer : packedPressure_)
        buffer = gpu::createBuffer(ctx, packedBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                   gpu::MemoryUsage::DeviceLocal, "packed pressure");
    packedDivergence_ = gpu::createBuffer(ctx, packedBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                          gpu::MemoryUsage::DeviceLocal, "packed divergence");
    vorticity_ = makeImage(cells_, VK_FORMAT_R32G32B32A32_SFLOAT, "vorticity");
    force_ = makeImage(cells_, VK_FORMAT_R32G32B32A32_SFLOAT, "confinement force");
    // Stages that write a whole field write it here first (shaders/fluid_common.glsl): one buffer
    // per velocity component, the first also large enough for four floats per cell.
    VkDeviceSize faceFloats = 0;
    for (int c = 0; c < 3; ++c) {
        const glm::uvec3 n = faceExtent(options.grid, c);
        faceFloats = std::max<VkDeviceSize>(faceFloats, VkDeviceSize(n.x) * n.y * n.z);
    }
    const VkDeviceSize cellFloats = VkDeviceSize(cells_.x) * cells_.y * cells_.z * 4;
    for (int c = 0; c < 3; ++c)
        scratch_[c] = gpu::createBuffer(
            ctx, (c == 0 ? std::max(faceFloats, cellFloats) : faceFloats) * sizeof(float),
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
            gpu::MemoryUsage::DeviceLocal, "field output");

    // Everything starts at rest, in GENERAL layout for the whole of its life.
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        auto clear = [&](gpu::Image& image) {
            gpu::transitionImage(cmd, image, VK_IMAGE_LAYOUT_GENERAL);
            const VkClearColorValue zero{};
            const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            vkCmdClearColorImage(cmd, image.get(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
        };
        for (auto& set : velocity_)
            for (auto& image : set)
                clear(image);
        for (auto& image : pigment_)
            clear(image);
        for (auto& image : pressure_)
            clear(image);
        clear(divergence_);
        clear(vorticity_);
        clear(force_);
        barrier(cmd);
    });

    parameters_ =
        gpu::createBuffer(ctx, sizeof(shared::FluidParameters), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                          gpu::MemoryUsage::Upload, "fluid parameters");
    ownEmitters_ = gpu::createBuffer(ctx, 16 * sizeof(shared::FluidEmitter),
                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload,
                                     "fluid emitters");
    emitterBuffer_ = ownEmitters_.get();
    emitterBufferSize_ = ownEmitters_.size;
    splatRegions_ =
        gpu::createBuffer(ctx, 4 * sizeof(shared::SplatRegion),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                          gpu::MemoryUsage::DeviceLocal, "fluid splat regions");

    writeParameters();
}

// Programs are compiled on first use: a solver that never runs a stage never pays for its
// pipeline (on a CPU driver each compile costs tens of milliseconds).
gpu::Program& SmokeSolver::program(Stage stage, int part, uint32_t target) {
    using namespace mfx::shaders;
    gpu::Program& slot = programs_[{int(stage), part, target}];
    if (slot.pipeline() != VK_NULL_HANDLE) return slot;
    switch (stage) {
    case Stage::SplatImpulses:
        slot = part == 0
                   ? makeProgram(ctx_, options_, "splat_impulses",
                                 MFX_FIELD_SHADER(splat_impulses_comp), target, 7, 1, {}, 1u << 6)
                   : makeProgram(ctx_, options_, "emitter_bounds", emitter_bounds_comp, 0, 3, 1, {},
                                 1u << 2);
        break;
    case Stage::AdvectVelocity: { // part: the pass (MFX_ADVECT_*), constant id 11
        const uint32_t pass[] = {uint32_t(part)};
        slot = makeProgram(ctx_, options_, "advect_velocity",
                           MFX_FIELD_SHADER(advect_velocity_comp), target, 6, 4, pass);
        break;
    }
    case Stage::AdvectPigment: {
        const uint32_t pass[] = {uint32_t(part)};
        slot = makeProgram(ctx_, options_, "advect_pigment", MFX_FIELD_SHADER(advect_pigment_comp),
                           target, 7, 5, pass);
        break;
    }
    case Stage::ApplyBuoyancy:
        slot = makeProgram(ctx_, options_, "apply_buoyancy", MFX_FIELD_SHADER(apply_buoyancy_comp),
                           target, 4, 3);
        break;
    case Stage::VorticityConfinement:
        slot = part == 0   ? makeProgram(ctx_, options_, "compute_vorticity",
                                         MFX_FIELD_SHADER(compute_vorticity_comp), target, 5, 4)
               : part == 1 ? makeProgram(ctx_, options_, "confinement_force",
                                         confinement_force_comp, target, 3, 2)
                           : makeProgram(ctx_, options_, "apply_vorticity_force",
                                         MFX_FIELD_SHADER(apply_vorticity_force_comp), target, 8, 0,
                                         {}, 0xe0u);
        break;
    case Stage::DiffuseViscosity:
        slot = makeProgram(ctx_, options_, "diffuse_viscosity",
                           MFX_FIELD_SHADER(diffuse_viscosity_comp), target, 10);
        break;
    case Stage::ApplyBoundaries:
        slot = makeProgram(ctx_, options_, "apply_boundaries",
                           MFX_FIELD_SHADER(apply_boundaries_comp), target, 4);
        break;
    case Stage::ComputeDivergence:
        slot = makeProgram(ctx_, options_, "compute_divergence",
                           MFX_FIELD_SHADER(compute_divergence_comp), target, 5, 4);
        break;
    case Stage::SolvePressure: {
        // Constant ids 11-13: which side is packed (part), the layers and rows of a brick;
        // bindings 4-7 are storage buffers.
        const uint32_t brick[] = {uint32_t(part), kPressureLayers, kPressureRows};
        slot = makeProgram(ctx_, options_, "solve_pressure", MFX_FIELD_SHADER(solve_pressure_comp),
                           target, 8, 0, brick, 0xf0u);
        break;
    }
    case Stage::Project:
        slot = makeProgram(ctx_, options_, "project", MFX_FIELD_SHADER(project_comp), target, 6, 5);
        break;
    }
    return slot;
}

void SmokeSolver::setState(const FieldState& state) {
    auto upload = [&](gpu::Image& image, const std::vector<float>& values) {
        if (isHalf(image.format)) { // rounded as every stage's store rounds
            std::vector<uint16_t> half(values.size());
            std::transform(values.begin(), values.end(), half.begin(), toHalfBits);
            gpu::uploadImage(ctx_, image, std::as_bytes(std::span<const uint16_t>(half)),
                             VK_IMAGE_LAYOUT_GENERAL);
            return;
        }
        gpu::uploadImage(ctx_, image, std::as_bytes(std::span<const float>(values)),
                         VK_IMAGE_LAYOUT_GENERAL);
    };
    upload(velocity_[currentVelocity_][0], state.velocityX);
    upload(velocity_[currentVelocity_][1], state.velocityY);
    upload(velocity_[currentVelocity_][2], state.velocityZ);
    upload(pressure_[currentPressure_], state.pressure);
    upload(divergence_, state.divergence);
    upload(pigment_[currentPigment_], state.pigment);
}

FieldState SmokeSolver::state() {
    auto read = [&](gpu::Image& image) {
        const std::vector<std::byte> bytes = gpu::readImage(ctx_, image);
        if (isHalf(image.format)) {
            std::vector<uint16_t> half(bytes.size() / sizeof(uint16_t));
            std::memcpy(half.data(), bytes.data(), half.size() * sizeof(uint16_t));
            std::vector<float> values(half.size());
            std::transform(half.begin(), half.end(), values.begin(), fromHalfBits);
            return values;
        }
        std::vector<float> values(bytes.size() / sizeof(float));
        std::memcpy(values.data(), bytes.data(), values.size() * sizeof(float));
        return values;
    };
    FieldState state;
    state.grid = options_.grid;
    state.velocityX = read(velocity_[currentVelocity_][0]);
    state.velocityY = read(velocity_[currentVelocity_][1]);
    state.velocityZ = read(velocity_[currentVelocity_][2]);
    state.pressure = read(pressure_[currentPressure_]);
    state.divergence = read(divergence_);
    state.pigment = read(pigment_[currentPigment_]);
    return state;
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
    if (buffer.get() != emitterBuffer_) {
        // The splat program's sets name the old buffer: drop them all.
        for (auto& [key, splat] : programs_) {
            if (std::get<0>(key) != int(Stage::SplatImpulses)) continue; // and emitter_bounds
            splat.resetSets(ctx_);
            std::erase_if(sets_,
                          [&](const auto& entry) { return std::get<0>(entry.first) == &splat; });
        }
        emitterBuffer_ = buffer.get();
        emitterBufferSize_ = buffer.size;
    }
    emitterCount_ = std::min<uint32_t>(count, uint32_t(buffer.size / sizeof(shared::FluidEmitter)));
}

void SmokeSolver::writeParameters() {
    const shared::FluidParameters parameters = makeParameters(options_, emitterCount_);
    std::memcpy(parameters_.mapped, &parameters, sizeof(parameters));
}

void SmokeSolver::barrier(VkCommandBuffer cmd) const {
    const VkPipelineStageFlags2 stages =
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    gpu::memoryBarrier(
        cmd, stages, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, stages,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
            VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

void SmokeSolver::dispatch(VkCommandBuffer cmd, gpu::Program& program, VkDescriptorSet set,
                           glm::uvec3 extent, glm::uvec3 origin) const {
    program.bind(cmd, set);
    const shared::FluidDispatch dispatch{0, origin.x, origin.y, origin.z};
    program.push(cmd, dispatch);
    ++dispatches_;
    const std::array<uint32_t, 3>& group = options_.workgroup;
    vkCmdDispatch(cmd, gpu::groupCount(extent.x, group[0]), gpu::groupCount(extent.y, group[1]),
                  gpu::groupCount(extent.z, group[2]));
}

void SmokeSolver::copyToImages(
    VkCommandBuffer cmd, std::initializer_list<std::pair<const gpu::Buffer*, gpu::Image*>> fields) {
    // A copy cannot convert: binary16 images are stored into by store_half instead.
    std::vector<std::pair<const gpu::Buffer*, gpu::Image*>> copies, converted;
    for (const auto& pair : fields)
        (isHalf(pair.second->format) ? converted : copies).push_back(pair);
    if (!converted.empty()) {
        barrier(cmd);
        for (const auto& [buffer, image] : converted) {
            const bool rgba = image->format == VK_FORMAT_R16G16B16A16_SFLOAT;
            gpu::Program& prog = storeHalf_[rgba ? 1 : 0];
            if (!prog.pipeline())
                prog = makeProgram(ctx_, options_, "store_half",
                                   rgba ? shaders::store_half_comp_rgba : shaders::store_half_comp,
                                   0, 3, 1);
            const auto key = std::make_pair(buffer->get(), image->get());
            auto it = storeHalfSets_.find(key);
            if (it == storeHalfSets_.end())
                it = storeHalfSets_
                         .emplace(key, prog.createSet(ctx_, {gpu::bindBuffer(0, parameters_),
                                                             gpu::bindBuffer(1, *buffer),
                                                             storage(2, *image)}))
                         .first;
            dispatch(cmd, prog, it->second,
                     glm::uvec3(image->extent.width, image->extent.height, image->extent.depth));
        }
        barrier(cmd);
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

template <typename MakeWrites>
VkDescriptorSet SmokeSolver::set(gpu::Program& program, std::tuple<int, int, int> key,
                                 MakeWrites makeWrites) {
    const auto fullKey = std::make_tuple(static_cast<const gpu::Program*>(&program),
                                         std::get<0>(key), std::get<1>(key), std::get<2>(key));
    if (auto it = sets_.find(fullKey); it != sets_.end()) return it->second;
    std::vector<gpu::DescriptorWrite> writes{gpu::bindBuffer(0, parameters_)};
    makeWrites(writes);
    VkDescriptorSet created = program.createSet(ctx_, writes);
    sets_.emplace(fullKey, created);
    return created;
}

void SmokeSolver::addVelocity(std::vector<gpu::DescriptorWrite>& writes, int velocitySet,
                              uint32_t firstBinding) const {
    for (uint32_t c = 0; c < 3; ++c)
        writes.push_back(storage(firstBinding + c, velocity_[velocitySet][c]));
}

// --- Stages -------------------------------------------------------------------------------------

void SmokeSolver::splatImpulses(VkCommandBuffer cmd) {
    if (emitterCount_ == 0) return;
    const int v = currentVelocity_, p = currentPigment_;
    gpu::DescriptorWrite emitters;
    emitters.binding = 1;
    emitters.buffer = {emitterBuffer_, 0, emitterBufferSize_};
    gpu::DescriptorWrite regions;
    regions.binding = 6;
    regions.buffer = {splatRegions_.get(), 0, splatRegions_.size};
    // The emitters' bounding box, per target, as indirect dispatches (emitters may be written on
    // the GPU, so only the GPU knows where they are).
    gpu::Program& bounds = program(Stage::SplatImpulses, 1);
    bounds.bind(cmd, set(bounds, {0, 0, 0}, [&](auto& w) {
                    w.push_back(emitters);
                    gpu::DescriptorWrite out = regions;
                    out.binding = 2;
                    w.push_back(out);
                }));
    ++dispatches_;
    vkCmdDispatch(cmd, 1, 1, 1);
    gpu::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
        VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
        VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    auto writes = [&](auto& w) {
        w.push_back(emitters);
        addVelocity(w, v, 2);
        w.push_back(storage(5, pigment_[p]));
        w.push_back(regions);
    };
    for (uint32_t target = 0; target < 4; ++target) {
        gpu::Program& prog = program(Stage::SplatImpulses, 0, target);
        prog.bind(cmd, set(prog, {v, p, 0}, writes));
        const shared::FluidDispatch unused{0, 0, 0, 0};
        prog.push(cmd, unused);
        ++dispatches_;
        vkCmdDispatchIndirect(cmd, splatRegions_.get(), target * sizeof(shared::SplatRegion));
    }
    barrier(cmd);
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
    const int from = currentVelocity_, to = 1 - currentVelocity_;
    for (uint32_t pass : advectionPasses()) {
        for (uint32_t c = 0; c < 3; ++c) {
            gpu::Program& prog = program(Stage::AdvectVelocity, int(pass), c);
            VkDescriptorSet s = set(prog, {from, 0, 0}, [&](auto& w) {
                addVelocity(w, from, 1);
                w.push_back(gpu::bindBuffer(4, scratch_[c]));
                w.push_back(storage(5, velocity_[to][c]));
            });
            dispatch(cmd, prog, s, faceExtent(options_.grid, int(c)));
        }
        copyToImages(cmd, {{&scratch_[0], &velocity_[to][0]},
                           {&scratch_[1], &velocity_[to][1]},
                           {&scratch_[2], &velocity_[to][2]}});
    }
    currentVelocity_ = to;
}

void SmokeSolver::advectPigment(VkCommandBuffer cmd) {
    const int v = currentVelocity_, from = currentPigment_, to = 1 - currentPigment_;
    for (uint32_t pass : advectionPasses()) {
        gpu::Program& prog = program(Stage::AdvectPigment, int(pass), MFX_TARGET_PIGMENT);
        VkDescriptorSet s = set(prog, {v, from, 0}, [&](auto& w) {
            addVelocity(w, v, 1);
            w.push_back(storage(4, pigment_[from]));
            w.push_back(gpu::bindBuffer(5, scratch_[0]));
            w.push_back(storage(6, pigment_[to]));
        });
        dispatch(cmd, prog, s, cells_);
        copyToImages(cmd, {{&scratch_[0], &pigment_[to]}});
    }
    currentPigment_ = to;
}

void SmokeSolver::applyBuoyancy(VkCommandBuffer cmd) {
    if (options_.buoyancy == 0.0f) return;
    const int v = currentVelocity_, p = currentPigment_;
    gpu::Program& prog = program(Stage::ApplyBuoyancy, 0, MFX_TARGET_VELOCITY_Y);
    VkDescriptorSet s = set(prog, {v, p, 0}, [&](auto& w) {
        w.push_back(storage(1, velocity_[v][1]));
        w.push_back(storage(2, pigment_[p]));
        w.push_back(gpu::bindBuffer(3, scratch_[1]));
    });
    dispatch(cmd, prog, s, faceExtent(options_.grid, 1));
    copyToImages(cmd, {{&scratch_[1], &velocity_[v][1]}});
}

void SmokeSolver::vorticityConfinement(VkCommandBuffer cmd) {
    if (options_.vorticity == 0.0f) return;
    // Vorticity per cell, then the confinement force per cell, then the faces.
    const int v = currentVelocity_;
    gpu::Program& compute = program(Stage::VorticityConfinement, 0, 0);
    dispatch(cmd, compute,
             set(compute, {v, 0, 0},
                 [&](auto& w) {
                     addVelocity(w, v, 1);
                     w.push_back(gpu::bindBuffer(4, scratch_[0]));
                 }),
             cells_);
    copyToImages(cmd, {{&scratch_[0], &vorticity_}});
    gpu::Program& force = program(Stage::VorticityConfinement, 1, 0);
    dispatch(cmd, force,
             set(force, {0, 0, 0},
                 [&](auto& w) {
                     w.push_back(storage(1, vorticity_));
                     w.push_back(gpu::bindBuffer(2, scratch_[0]));
                 }),
             cells_);
    copyToImages(cmd, {{&scratch_[0], &force_}});
    gpu::Program& apply = program(Stage::VorticityConfinement, 2, 0);
    dispatch(cmd, apply,
             set(apply, {v, 0, 0},
                 [&](auto& w) {
                     addVelocity(w, v, 1);
                     w.push_back(storage(4, force_));
                     for (uint32_t c = 0; c < 3; ++c)
                         w.push_back(gpu::bindBuffer(5 + c, scratch_[c]));
                 }),
             cells_ + glm::uvec3(1));
    copyToImages(cmd, {{&scratch_[0], &velocity_[v][0]},
                       {&scratch_[1], &velocity_[v][1]},
                       {&scratch_[2], &velocity_[v][2]}});
}

void SmokeSolver::diffuseViscosity(VkCommandBuffer cmd) {
    const uint32_t sweeps = options_.viscosityIterations;
    if (options_.viscosity == 0.0f || sweeps == 0) return;
    const int source = currentVelocity_, other = 1 - currentVelocity_, scratch = 2;
    // Alternate between `other` and the scratch set so that the last sweep lands in `other`.
    int in = source;
    int out = sweeps % 2 == 1 ? other : scratch;
    for (uint32_t sweep = 0; sweep < sweeps; ++sweep) {
        auto writes = [&](auto& w) {
            addVelocity(w, source, 1);
            addVelocity(w, in, 4);
            addVelocity(w, out, 7);
        };
        for (uint32_t c = 0; c < 3; ++c) {
            gpu::Program& prog = program(Stage::DiffuseViscosity, 0, c);
            dispatch(cmd, prog, set(prog, {source, in, out}, writes),
                     faceExtent(options_.grid, int(c)));
        }
        barrier(cmd);
        in = out;
        out = out == other ? scratch : other;
    }
    currentVelocity_ = other;
}

void SmokeSolver::applyBoundaries(VkCommandBuffer cmd) {
    const int v = currentVelocity_;
    for (uint32_t c = 0; c < 3; ++c) {
        gpu::Program& prog = program(Stage::ApplyBoundaries, 0, c);
        glm::uvec3 layers = faceExtent(options_.grid, int(c));
        layers[int(c)] = 2; // only the two boundary layers of faces normal to c
        dispatch(cmd, prog, set(prog, {v, 0, 0}, [&](auto& w) { addVelocity(w, v, 1); }), layers);
    }
    barrier(cmd);
}

void SmokeSolver::computeDivergence(VkCommandBuffer cmd) {
    const int v = currentVelocity_;
    gpu::Program& prog = program(Stage::ComputeDivergence);
    VkDescriptorSet s = set(prog, {v, 0, 0}, [&](auto& w) {
        addVelocity(w, v, 1);
        w.push_back(gpu::bindBuffer(4, scratch_[0]));
    });
    dispatch(cmd, prog, s, cells_);
    copyToImages(cmd, {{&scratch_[0], &divergence_}});
}

void SmokeSolver::solvePressure(VkCommandBuffer cmd) {
    if (multigrid_) {
        // The other solvers write the solution x-fastest into a buffer, copied over the live image.
        dispatches_ +=
            multigrid_->record(cmd, divergence_, pressure_[currentPressure_], scratch_[0]);
        copyToImages(cmd, {{&scratch_[0], &pressure_[currentPressure_]}});
        return;
    }
    if (!options_.warmStart) {
        const VkClearColorValue zero{};
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, pressure_[currentPressure_].get(), VK_IMAGE_LAYOUT_GENERAL, &zero,
                             1, &range);
        barrier(cmd);
    }
    // Bricks of 4 x kPressureRows x kPressureLayers cells. Between the first and the last sweep
    // pressure and divergence live packed (shaders/solve_pressure.comp): the first sweep reads
    // the live r32f image, the last writes the other one.
    const uint32_t sweeps = options_.jacobiIterations;
    const glm::uvec3 bricks((cells_.x + kPressureBrickX - 1) / kPressureBrickX,
                            (cells_.y + kPressureRows - 1) / kPressureRows,
                            (cells_.z + kPressureLayers - 1) / kPressureLayers);
    int packedIn = 0;
    for (uint32_t sweep = 0; sweep < sweeps; ++sweep) {
        const bool first = sweep == 0, last = sweep + 1 == sweeps;
        const uint32_t mode = packedSolve_ ? (first ? 0u : 1u) | (last ? 0u : 2u) : 0u;
        gpu::Program& prog = program(Stage::SolvePressure, int(mode));
        const int in = currentPressure_, out = 1 - currentPressure_;
        const int packedOut = 1 - packedIn;
        VkDescriptorSet s = set(prog, {in, packedIn, 0}, [&](auto& w) {
            w.push_back(storage(1, divergence_));
            w.push_back(storage(2, pressure_[in]));
            w.push_back(storage(3, pressure_[out]));
            w.push_back(gpu::bindBuffer(4, packedDivergence_));
            w.push_back(gpu::bindBuffer(5, packedPressure_[packedIn]));
            w.push_back(gpu::bindBuffer(6, packedPressure_[packedOut]));
            w.push_back(gpu::bindBuffer(7, packedPressure_[packedIn]));
        });
        dispatch(cmd, prog, s, bricks);
        barrier(cmd);
        if (mode & 2u)
            packedIn = packedOut;
        else
            currentPressure_ = out; // this sweep wrote the other r32f image
    }
}

void SmokeSolver::project(VkCommandBuffer cmd) {
    const int v = currentVelocity_, p = currentPressure_;
    for (uint32_t c = 0; c < 3; ++c) {
        gpu::Program& prog = program(Stage::Project, 0, c);
        VkDescriptorSet s = set(prog, {v, p, 0}, [&](auto& w) {
            addVelocity(w, v, 1);
            w.push_back(storage(4, pressure_[p]));
            w.push_back(gpu::bindBuffer(5, scratch_[c]));
        });
        dispatch(cmd, prog, s, faceExtent(options_.grid, int(c)));
    }
    copyToImages(cmd, {{&scratch_[0], &velocity_[v][0]},
                       {&scratch_[1], &velocity_[v][1]},
                       {&scratch_[2], &velocity_[v][2]}});
}

// --- Recording
// ------------------------------------------------------------------------------------

void SmokeSolver::recordStage(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer) {
    writeParameters();
    recordStageOnly(cmd, stage, timer);
}

void SmokeSolver::recordStageOnly(VkCommandBuffer cmd, Stage stage, gpu::GpuTimer* timer) {
    if (timer) timer->begin(cmd, stageName(stage));
    switch (stage) {
    case Stage::SplatImpulses:
        splatImpulses(cmd);
        break;
    case Stage::AdvectVelocity:
        advectVelocity(cmd);
        break;
    case Stage::AdvectPigment:
        advectPigment(cmd);
        break;
    case Stage::ApplyBuoyancy:
        applyBuoyancy(cmd);
        break;
    case Stage::VorticityConfinement:
        vorticityConfinement(cmd);
        break;
    case Stage::DiffuseViscosity:
        diffuseViscosity(cmd);
        break;
    case Stage::ApplyBoundaries:
        applyBoundaries(cmd);
        break;
    case Stage::ComputeDivergence:
        computeDivergence(cmd);
        break;
    case Stage::SolvePressure:
        solvePressure(cmd);
        break;
    case Stage::Project:
        project(cmd);
        break;
    }
    if (timer) timer->end(cmd);
}

void SmokeSolver::recordStep(VkCommandBuffer cmd, gpu::GpuTimer* timer) {
    writeParameters(); // once: every sub-step and stage reads the same uniform
    lastStepDispatches_.clear();
    for (uint32_t substep = 0; substep < options_.substeps; ++substep)
        for (Stage stage : kStepOrder) {
            const uint32_t before = dispatches_;
            recordStageOnly(cmd, stage, timer);
            const std::string name = stageName(stage);
            auto it = std::find_if(lastStepDispatches_.begin(), lastStepDispatches_.end(),
                                   [&](const auto& entry) { return entry.first == name; });
            if (it == lastStepDispatches_.end())
                lastStepDispatches_.emplace_back(name, dispatches_ - before);
            else
                it->second += dispatches_ - before;
        }
}

uint64_t SmokeSolver::memoryBytes() const {
    uint64_t bytes = 0;
    auto image = [&](const gpu::Image& i) {
        if (i)
            bytes += uint64_t(i.extent.width) * i.extent.height * i.extent.depth *
                     gpu::formatTexelSize(i.format);
    };
    for (const auto& set : velocity_)
        for (const gpu::Image& i : set)
            image(i);
    for (const gpu::Image& i : pigment_)
        image(i);
    for (const gpu::Image& i : pressure_)
        image(i);
    image(divergence_);
    image(vorticity_);
    image(force_);
    for (const gpu::Buffer& b : scratch_)
        bytes += b.size;
    for (const gpu::Buffer& b : packedPressure_)
        bytes += b.size;
    bytes += packedDivergence_.size + parameters_.size + ownEmitters_.size;
    if (multigrid_) bytes += multigrid_->memoryBytes();
    return bytes;
}

void SmokeSolver::recordMeasureActivity(VkCommandBuffer cmd, const gpu::Buffer& out) {
    if (!activityProgram_.pipeline())
        activityProgram_ = makeProgram(ctx_, options_, "measure_activity",
                                       MFX_FIELD_SHADER(shaders::measure_activity_comp), 0, 6, 5);
    vkCmdFillBuffer(cmd, out.get(), 0, 2 * sizeof(uint32_t), 0);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    const auto key = std::make_tuple(currentVelocity_, currentPigment_, out.get());
    auto it = activitySets_.find(key);
    if (it == activitySets_.end()) {
        std::vector<gpu::DescriptorWrite> writes{gpu::bindBuffer(0, parameters_)};
        addVelocity(writes, currentVelocity_, 1);
        writes.push_back(storage(4, pigment_[currentPigment_]));
        writes.push_back(gpu::bindBuffer(5, out));
        it = activitySets_.emplace(key, activityProgram_.createSet(ctx_, writes)).first;
    }
    dispatch(cmd, activityProgram_, it->second, cells_);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                       VK_ACCESS_2_HOST_READ_BIT);
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

void SmokeSolver::recordShift(VkCommandBuffer cmd, glm::ivec3 cells) {
    if (cells == glm::ivec3(0)) return;
    gpu::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
            VK_ACCESS_2_TRANSFER_WRITE_BIT,
        VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
        VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
    // Each field into its ping-pong partner: cleared, then the overlap copied across.
    auto shift = [&](const gpu::Image& from, const gpu::Image& to) {
        const VkClearColorValue zero{};
        VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, to.get(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
        const glm::ivec3 size(int(from.extent.width), int(from.extent.height),
                              int(from.extent.depth));
        const glm::ivec3 extent = size - glm::abs(cells);
        if (glm::any(glm::lessThanEqual(extent, glm::ivec3(0)))) return; // moved past it all
        const glm::ivec3 src = glm::max(cells, glm::ivec3(0));
        const glm::ivec3 dst = glm::max(-cells, glm::ivec3(0));
        VkImageCopy region{};
        region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.dstSubresource = region.srcSubresource;
        region.srcOffset = {src.x, src.y, src.z};
        region.dstOffset = {dst.x, dst.y, dst.z};
        region.extent = {uint32_t(extent.x), uint32_t(extent.y), uint32_t(extent.z)};
        gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                           VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                           VK_ACCESS_2_TRANSFER_WRITE_BIT);
        vkCmdCopyImage(cmd, from.get(), VK_IMAGE_LAYOUT_GENERAL, to.get(), VK_IMAGE_LAYOUT_GENERAL,
                       1, &region);
    };
    for (int c = 0; c < 3; ++c)
        shift(velocity_[size_t(currentVelocity_)][size_t(c)],
              velocity_[size_t(1 - currentVelocity_)][size_t(c)]);
    shift(pigment_[size_t(currentPigment_)], pigment_[size_t(1 - currentPigment_)]);
    shift(pressure_[size_t(currentPressure_)], pressure_[size_t(1 - currentPressure_)]);
    currentVelocity_ = 1 - currentVelocity_;
    currentPigment_ = 1 - currentPigment_;
    currentPressure_ = 1 - currentPressure_;
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                           VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                           VK_ACCESS_2_TRANSFER_READ_BIT);
}

} // namespace mfx::fluid
