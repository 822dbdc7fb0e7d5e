#include "fluid/smoke_fields.h"

#include "core/gpu/commands.h"
#include "core/gpu/context.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace mfx::fluid {

namespace {

// Sampled too: a renderer ray-marches the pigment (in GENERAL layout, as the solver keeps it).
constexpr VkImageUsageFlags kFieldUsage =
    VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
    VK_IMAGE_USAGE_SAMPLED_BIT;

} // namespace

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

void fieldBarrier(VkCommandBuffer cmd) {
    const VkPipelineStageFlags2 stages =
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    gpu::memoryBarrier(
        cmd, stages, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT, stages,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
            VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

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

SmokeFields::SmokeFields(const gpu::Context& ctx, const SolverOptions& options)
    : cells(options.grid.cellsX, options.grid.cellsY, options.grid.cellsZ) {
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
            velocity[set][c] =
                makeImage(faceExtent(options.grid, c), scalarFormat(options), "velocity");
    for (int i = 0; i < 2; ++i) {
        pigment[i] = makeImage(cells, rgbaFormat(options), "pigment");
        pressure[i] = makeImage(cells, scalarFormat(options), "pressure");
    }
    divergence = makeImage(cells, VK_FORMAT_R32_SFLOAT, "divergence");
    // Four x-consecutive cells per vec4 (shaders/fluid/solve_pressure.comp). A grid too large for
    // one storage buffer solves on the r32f images alone (placeholders fill the unused bindings).
    VkDeviceSize packedBytes = VkDeviceSize((cells.x + kPressureBrickX - 1) / kPressureBrickX) *
                               cells.y * cells.z * 4 * sizeof(float);
    packedSolve = packedBytes <= ctx.limits().maxStorageBufferRange;
    if (!packedSolve) packedBytes = 4 * sizeof(float);
    for (gpu::Buffer& buffer : packedPressure)
        buffer = gpu::createBuffer(ctx, packedBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                   gpu::MemoryUsage::DeviceLocal, "packed pressure");
    packedDivergence = gpu::createBuffer(ctx, packedBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                         gpu::MemoryUsage::DeviceLocal, "packed divergence");
    vorticity = makeImage(cells, VK_FORMAT_R32G32B32A32_SFLOAT, "vorticity");
    force = makeImage(cells, VK_FORMAT_R32G32B32A32_SFLOAT, "confinement force");
    // Stages that write a whole field write it here first (shaders/fluid/fluid_common.glsl): one
    // buffer per velocity component, the first also large enough for four floats per cell.
    VkDeviceSize faceFloats = 0;
    for (int c = 0; c < 3; ++c) {
        const glm::uvec3 n = faceExtent(options.grid, c);
        faceFloats = std::max<VkDeviceSize>(faceFloats, VkDeviceSize(n.x) * n.y * n.z);
    }
    const VkDeviceSize cellFloats = VkDeviceSize(cells.x) * cells.y * cells.z * 4;
    for (int c = 0; c < 3; ++c)
        scratch[c] = gpu::createBuffer(
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
        for (auto& set : velocity)
            for (auto& image : set)
                clear(image);
        for (auto& image : pigment)
            clear(image);
        for (auto& image : pressure)
            clear(image);
        clear(divergence);
        clear(vorticity);
        clear(force);
        fieldBarrier(cmd);
    });
}

void SmokeFields::upload(const gpu::Context& ctx, const FieldState& state) {
    auto upload = [&](gpu::Image& image, const std::vector<float>& values) {
        if (isHalf(image.format)) { // rounded as every stage's store rounds
            std::vector<uint16_t> half(values.size());
            std::transform(values.begin(), values.end(), half.begin(), toHalfBits);
            gpu::uploadImage(ctx, image, std::as_bytes(std::span<const uint16_t>(half)),
                             VK_IMAGE_LAYOUT_GENERAL);
            return;
        }
        gpu::uploadImage(ctx, image, std::as_bytes(std::span<const float>(values)),
                         VK_IMAGE_LAYOUT_GENERAL);
    };
    upload(velocity[currentVelocity][0], state.velocityX);
    upload(velocity[currentVelocity][1], state.velocityY);
    upload(velocity[currentVelocity][2], state.velocityZ);
    upload(pressure[currentPressure], state.pressure);
    upload(divergence, state.divergence);
    upload(pigment[currentPigment], state.pigment);
}

FieldState SmokeFields::download(const gpu::Context& ctx, const GridShape& grid) {
    auto read = [&](gpu::Image& image) {
        const std::vector<std::byte> bytes = gpu::readImage(ctx, image);
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
    state.grid = grid;
    state.velocityX = read(velocity[currentVelocity][0]);
    state.velocityY = read(velocity[currentVelocity][1]);
    state.velocityZ = read(velocity[currentVelocity][2]);
    state.pressure = read(pressure[currentPressure]);
    state.divergence = read(divergence);
    state.pigment = read(pigment[currentPigment]);
    return state;
}

uint64_t SmokeFields::memoryBytes() const {
    uint64_t bytes = 0;
    auto image = [&](const gpu::Image& i) {
        if (i)
            bytes += uint64_t(i.extent.width) * i.extent.height * i.extent.depth *
                     gpu::formatTexelSize(i.format);
    };
    for (const auto& set : velocity)
        for (const gpu::Image& i : set)
            image(i);
    for (const gpu::Image& i : pigment)
        image(i);
    for (const gpu::Image& i : pressure)
        image(i);
    image(divergence);
    image(vorticity);
    image(force);
    for (const gpu::Buffer& b : scratch)
        bytes += b.size;
    for (const gpu::Buffer& b : packedPressure)
        bytes += b.size;
    bytes += packedDivergence.size;
    return bytes;
}

void SmokeFields::recordShift(VkCommandBuffer cmd, glm::ivec3 by) {
    if (by == glm::ivec3(0)) return;
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
        const glm::ivec3 extent = size - glm::abs(by);
        if (glm::any(glm::lessThanEqual(extent, glm::ivec3(0)))) return; // moved past it all
        const glm::ivec3 src = glm::max(by, glm::ivec3(0));
        const glm::ivec3 dst = glm::max(-by, glm::ivec3(0));
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
        shift(velocity[size_t(currentVelocity)][size_t(c)],
              velocity[size_t(1 - currentVelocity)][size_t(c)]);
    shift(pigment[size_t(currentPigment)], pigment[size_t(1 - currentPigment)]);
    shift(pressure[size_t(currentPressure)], pressure[size_t(1 - currentPressure)]);
    currentVelocity = 1 - currentVelocity;
    currentPigment = 1 - currentPigment;
    currentPressure = 1 - currentPressure;
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT |
                           VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
                           VK_ACCESS_2_TRANSFER_READ_BIT);
}

} // namespace mfx::fluid
