// The fields of one GPU smoke grid: the MAC grid's images and the buffers the stages write
// through, with the state exchange (FieldState in and out, binary16 rounding included), the
// memory they take and the whole-cell shift of a grid that follows a character. What the fields
// mean and how they are stored: docs/fluid.md, "Grid"; who uses them: fluid/smoke_solver.h.
#pragma once

#include "core/gpu/resources.h"
#include "fluid/solver_options.h"

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

namespace mfx::gpu {
class Context;
}

namespace mfx::fluid {

// Cells per solve_pressure invocation: 4 along x (fixed by the shader, and the cells per element
// of the packed buffers) by kPressureRows along y by kPressureLayers along z.
inline constexpr uint32_t kPressureBrickX = 4;
inline constexpr uint32_t kPressureRows = 4;
inline constexpr uint32_t kPressureLayers = 4;

// The formats of the stored fields for the options' storage: velocity and pressure (r32f or
// r16f), pigment (rgba32f or rgba16f).
VkFormat scalarFormat(const SolverOptions& options);
VkFormat rgbaFormat(const SolverOptions& options);
bool isHalf(VkFormat format);

// IEEE 754-2008 binary16 bits of `v`, rounded to nearest with ties to even (the rounding of
// fluid/reference/half_storage.cpp); magnitudes that round above 65504 become infinite. And back.
uint16_t toHalfBits(float v);
float fromHalfBits(uint16_t h);

// Records the dependency between the fields' writes (compute stores, transfers) and every later
// read or write of them: what separates the solver's dispatches and copies.
void fieldBarrier(VkCommandBuffer cmd);

// Every field lives in a 3D storage image in GENERAL layout for the whole of its life, starting
// at rest. Velocity, pigment and pressure ping-pong between two images; current* says which is
// live.
struct SmokeFields {
    SmokeFields(const gpu::Context& ctx, const SolverOptions& options);

    glm::uvec3 cells{0};
    // velocity[set][component]: sets 0 and 1 ping-pong, set 2 is scratch for viscosity sweeps.
    std::array<std::array<gpu::Image, 3>, 3> velocity;
    std::array<gpu::Image, 2> pigment;
    std::array<gpu::Image, 2> pressure;
    gpu::Image divergence;
    gpu::Image vorticity;
    gpu::Image force; // vorticity confinement force per cell (xyz)
    // Where stages that write a whole field write it before it is copied into the field's image
    // (shaders/fluid/fluid_common.glsl): one per velocity component, the first large enough for the
    // pigment.
    std::array<gpu::Buffer, 3> scratch;
    // The Jacobi pressure solve's working copies, four cells per vec4
    // (shaders/fluid/solve_pressure.comp): pressure (ping-pong) and divergence; packedSolve is
    // false for a grid too large for one storage buffer (placeholders then fill the unused
    // bindings).
    std::array<gpu::Buffer, 2> packedPressure;
    gpu::Buffer packedDivergence;
    bool packedSolve = true;
    int currentVelocity = 0;
    int currentPigment = 0;
    int currentPressure = 0;

    // Uploads / reads back the live fields (waits for the GPU).
    void upload(const gpu::Context& ctx, const FieldState& state);
    FieldState download(const gpu::Context& ctx, const GridShape& grid);

    // Records a move by whole cells: afterwards field(q) holds what field(q + cells) held
    // (velocity, pigment and pressure), and what comes in from outside is 0.
    void recordShift(VkCommandBuffer cmd, glm::ivec3 by);

    // Bytes of GPU memory of the images and buffers.
    uint64_t memoryBytes() const;
};

} // namespace mfx::fluid
