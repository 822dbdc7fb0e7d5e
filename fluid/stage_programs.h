// The compute programs of the smoke solver's stages, from one table: each kernel's name (its
// shader file, shaders/fluid/<name>.comp), its SPIR-V for fp32 and fp16 storage, and which
// specialization constants it takes beyond the common ones. The binding layout of every program
// is read from its SPIR-V (core/gpu/spirv_bindings.h). Programs are compiled on first use: a
// solver that never runs a stage never pays for its pipeline (on a CPU driver each compile costs
// tens of milliseconds).
#pragma once

#include "core/gpu/program.h"
#include "fluid/solver_options.h"

#include <cstdint>
#include <map>
#include <string_view>
#include <tuple>

namespace mfx::gpu {
class Context;
}

namespace mfx::fluid {

class StagePrograms {
public:
    StagePrograms(const gpu::Context& ctx, const SolverOptions& options);

    // The program of kernel `name` for target field `target` (MFX_TARGET_*, constant id 0) and
    // `variant` (the advection pass, MFX_ADVECT_*, or the Jacobi sweep's packing; constant id 11
    // for the kernels that take one, ignored by the others), storing its whole-field output
    // straight into the image with `direct` (constant id 14, kDirectStore). An unknown name
    // throws std::logic_error. `blockList` (constant id 16, kBlockList) is the block list its
    // workgroups walk (shaders/fluid/fluid_solids.glsl; 0: none).
    gpu::Program& get(std::string_view name, uint32_t target = 0, uint32_t variant = 0,
                      bool direct = false, uint32_t blockList = 0);
    // Whether the programs get() returns from now on take the sub-step's solids into account
    // (constant id 15, kSolids: shaders/fluid/fluid_solids.glsl); without, a stage compiles as if
    // solids did not exist.
    void setSolids(bool solids) { solids_ = solids; }
    bool solids() const { return solids_; }

private:
    const gpu::Context& ctx_;
    SolverOptions options_;
    bool solids_ = false;
    std::map<std::tuple<std::string_view, uint32_t, uint32_t, bool, bool, uint32_t>, gpu::Program>
        programs_;
};

} // namespace mfx::fluid
