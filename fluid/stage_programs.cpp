#include "fluid/stage_programs.h"

#include "fluid/smoke_fields.h"
#include "shaders/embedded.h"
#include "shaders/shared/fluid.h"

#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace mfx::fluid {

namespace {

// What a kernel takes from constant id 11 on.
enum class Extra {
    None,
    Variant,       // id 11: the variant (an advection pass, the divergence's first sweep)
    PressureBrick, // ids 11-13: the variant (which side is packed), a brick's layers and rows
};

struct Kernel {
    std::string_view name;
    std::span<const uint32_t> spirv;
    std::span<const uint32_t> half; // empty: the kernel stores no field, fp32 code serves both
    Extra extra = Extra::None;
};

// Every kernel of the solver's stages (fluid/smoke_solver.cpp), plus the fp16 stores and the
// activity measurement. A function, not a table at namespace scope: the spans are defined in
// another translation unit.
const Kernel* findKernel(std::string_view name) {
    using namespace mfx::shaders;
    static const Kernel kernels[] = {
        {"mark_solids", mark_solids_comp, mark_solids_comp_half, Extra::Variant},
        {"emitter_bounds", emitter_bounds_comp, {}},
        {"splat_impulses", splat_impulses_comp, splat_impulses_comp_half},
        {"advect_velocity", advect_velocity_comp, advect_velocity_comp_half, Extra::Variant},
        {"advect_pigment", advect_pigment_comp, advect_pigment_comp_half, Extra::Variant},
        {"apply_buoyancy", apply_buoyancy_comp, apply_buoyancy_comp_half},
        {"turbulence_potential", turbulence_potential_comp, {}},
        {"apply_turbulence", apply_turbulence_comp, apply_turbulence_comp_half},
        {"compute_vorticity", compute_vorticity_comp, compute_vorticity_comp_half},
        {"confinement_force", confinement_force_comp, {}},
        {"apply_vorticity_force", apply_vorticity_force_comp, apply_vorticity_force_comp_half},
        {"vorticity_force", vorticity_force_comp, vorticity_force_comp_half},
        {"diffuse_viscosity", diffuse_viscosity_comp, diffuse_viscosity_comp_half},
        {"apply_boundaries", apply_boundaries_comp, apply_boundaries_comp_half},
        {"compute_divergence", compute_divergence_comp, compute_divergence_comp_half,
         Extra::Variant},
        {"solve_pressure", solve_pressure_comp, solve_pressure_comp_half, Extra::PressureBrick},
        {"project", project_comp, project_comp_half},
        {"measure_activity", measure_activity_comp, measure_activity_comp_half},
        {"store_half", store_half_comp, {}},
        {"store_half_rgba", store_half_comp_rgba, {}},
    };
    for (const Kernel& kernel : kernels)
        if (kernel.name == name) return &kernel;
    return nullptr;
}

} // namespace

StagePrograms::StagePrograms(const gpu::Context& ctx, const SolverOptions& options)
    : ctx_(ctx), options_(options) {}

gpu::Program& StagePrograms::get(std::string_view name, uint32_t target, uint32_t variant,
                                 bool direct, uint32_t blockList) {
    const Kernel* kernel = findKernel(name);
    if (kernel == nullptr)
        throw std::logic_error("the smoke solver has no kernel " + std::string(name));
    if (kernel->extra == Extra::None) variant = 0;
    gpu::Program& slot = programs_[{kernel->name, target, variant, direct, solids_, blockList}];
    if (slot.pipeline() != VK_NULL_HANDLE) return slot;

    gpu::ComputeProgramDesc desc;
    desc.name = kernel->name.data(); // the table's literals are NUL-terminated
    desc.spirv = options_.storage == Storage::Float16 && !kernel->half.empty() ? kernel->half
                                                                               : kernel->spirv;
    desc.pushConstantSize = sizeof(shared::FluidDispatch);
    // Constant ids as in shaders/fluid/fluid_common.glsl: the target, the six boundary kinds, the
    // integrator, then the workgroup shape (ids 8-10).
    desc.specialization = {target};
    for (const FaceBoundary& face : options_.boundaries)
        desc.specialization.push_back(uint32_t(face.kind));
    desc.specialization.push_back(uint32_t(options_.integrator));
    for (uint32_t size : options_.workgroup)
        desc.specialization.push_back(size);
    if (kernel->extra == Extra::Variant) desc.specialization.push_back(variant);
    if (kernel->extra == Extra::PressureBrick)
        desc.specialization.insert(desc.specialization.end(),
                                   {variant, kPressureLayers, kPressureRows});
    desc.specialization.resize(14, 0u); // ids 11-13 a kernel does not take are ignored
    desc.specialization.push_back(direct ? 1u : 0u);
    desc.specialization.push_back(solids_ ? 1u : 0u); // id 15, kSolids
    desc.specialization.push_back(blockList);         // id 16, kBlockList
    slot = gpu::createComputeProgram(ctx_, desc);
    return slot;
}

} // namespace mfx::fluid
