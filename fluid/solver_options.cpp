#include "fluid/solver_options.h"

#include "shaders/shared/sparse_fluid.h"

#include "core/enum_names.h"

#include <cmath>

namespace mfx::fluid {

namespace {

bool finite(float x) {
    return std::isfinite(x);
}
bool finite(const glm::vec4& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}
bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

const char* kFaceNames[6] = {"-x", "+x", "-y", "+y", "-z", "+z"};

} // namespace

Status validateOptions(const SolverOptions& o, uint32_t maxDimension, uint32_t maxInvocations) {
    if (Status grid = validateGrid(o.grid, maxDimension); !grid) return grid;
    auto bad = [](const std::string& what) { return Status(Error{what}); };
    if (!finite(o.dt) || o.dt < 0.0f) return bad("dt must be a finite number >= 0");
    if (o.substeps < 1 || o.substeps > 64) return bad("substeps must be between 1 and 64");
    if (!finite(o.fade) || o.fade < 0.0f) return bad("fade must be a finite number >= 0");
    if (!finite(o.drag) || o.drag < 0.0f) return bad("drag must be a finite number >= 0");
    if (!finite(o.buoyancy)) return bad("buoyancy must be finite");
    if (!finite(o.vorticity) || o.vorticity < 0.0f)
        return bad("vorticity must be a finite number >= 0");
    if (!finite(o.viscosity) || o.viscosity < 0.0f)
        return bad("viscosity must be a finite number >= 0");
    if (!finite(o.turbulence) || o.turbulence < 0.0f)
        return bad("turbulence must be a finite number >= 0");
    if (!finite(o.turbulenceScale) || o.turbulenceScale <= 0.0f)
        return bad("turbulenceScale must be a finite number > 0");
    if (!finite(o.turbulenceSpeed) || o.turbulenceSpeed < 0.0f)
        return bad("turbulenceSpeed must be a finite number >= 0");
    if (o.viscosityIterations > 10000) return bad("viscosityIterations must be at most 10000");
    if (o.jacobiIterations > 100000) return bad("jacobiIterations must be at most 100000");
    if (o.multigrid.levels > 16) return bad("multigrid levels must be at most 16");
    if (o.multigrid.preSmooth > 100 || o.multigrid.postSmooth > 100)
        return bad("multigrid smoothing sweeps must be at most 100");
    if (o.multigrid.cycles > 1000) return bad("multigrid cycles must be at most 1000");
    if (o.multigrid.coarseGroup > maxInvocations)
        return bad("multigrid coarseGroup " + std::to_string(o.multigrid.coarseGroup) +
                   " exceeds the device's " + std::to_string(maxInvocations) +
                   " invocations per workgroup");
    if (o.multigrid.coarseCells > 4096)
        return bad("multigrid coarseCells " + std::to_string(o.multigrid.coarseCells) +
                   " must be at most 4096 (16³), or 0 for that");
    if (o.multigrid.brick != 0 && o.multigrid.brick != 1 && o.multigrid.brick != 2 &&
        o.multigrid.brick != 4)
        return bad("multigrid brick " + std::to_string(o.multigrid.brick) +
                   " must be 1, 2 or 4 (or 0: by device)");
    if (!finite(o.cgTolerance) || o.cgTolerance < 0.0f)
        return bad("cgTolerance must be a finite number >= 0");
    if (o.cgMaxIterations > 10000) return bad("cgMaxIterations must be at most 10000");
    const uint64_t invocations =
        uint64_t(o.workgroup[0]) * uint64_t(o.workgroup[1]) * uint64_t(o.workgroup[2]);
    if (invocations == 0 || invocations > maxInvocations)
        return bad("workgroup " + std::to_string(o.workgroup[0]) + "x" +
                   std::to_string(o.workgroup[1]) + "x" + std::to_string(o.workgroup[2]) +
                   " must have between 1 and " + std::to_string(maxInvocations) + " invocations");
    for (int face = 0; face < 6; ++face) {
        const glm::vec3 w = o.boundaries[face].wallVelocity;
        if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z))
            return bad(std::string("boundary ") + kFaceNames[face] +
                       ": wall velocity must be finite");
    }
    for (int axis = 0; axis < 3; ++axis) {
        const bool low = o.boundaries[2 * axis].kind == Boundary::Periodic;
        const bool high = o.boundaries[2 * axis + 1].kind == Boundary::Periodic;
        if (low != high)
            return bad(std::string("boundary ") + kFaceNames[2 * axis] + "/" +
                       kFaceNames[2 * axis + 1] + ": periodic must be set on both faces");
    }
    return Ok{};
}

namespace {

constexpr NamedValue<PressureSolver> kPressureSolverNames[] = {
    {PressureSolver::Jacobi, "jacobi"},
    {PressureSolver::RedBlackGaussSeidel, "rbgs"},
    {PressureSolver::Multigrid, "multigrid"},
    {PressureSolver::MultigridPcg, "mgpcg"}};
constexpr NamedValue<AdvectionScheme> kAdvectionNames[] = {
    {AdvectionScheme::SemiLagrangian, "semi-lagrangian"},
    {AdvectionScheme::MacCormack, "maccormack"},
    {AdvectionScheme::Bfecc, "bfecc"}};
constexpr NamedValue<Storage> kStorageNames[] = {{Storage::Float32, "fp32"},
                                                 {Storage::Float16, "fp16"}};
constexpr NamedValue<StorePath> kStorePathNames[] = {
    {StorePath::Auto, "auto"}, {StorePath::Buffer, "buffer"}, {StorePath::Direct, "direct"}};
constexpr NamedValue<ByDevice> kByDeviceNames[] = {
    {ByDevice::Auto, "auto"}, {ByDevice::Off, "off"}, {ByDevice::On, "on"}};
} // namespace

const char* pressureSolverName(PressureSolver solver) {
    return nameOf(solver, kPressureSolverNames);
}

std::optional<PressureSolver> pressureSolverFromName(std::string_view name) {
    return valueOf(name, kPressureSolverNames);
}

const char* advectionName(AdvectionScheme scheme) {
    return nameOf(scheme, kAdvectionNames);
}

std::optional<AdvectionScheme> advectionFromName(std::string_view name) {
    return valueOf(name, kAdvectionNames);
}

const char* storageName(Storage storage) {
    return nameOf(storage, kStorageNames, "fp32");
}

std::optional<Storage> storageFromName(std::string_view name) {
    return valueOf(name, kStorageNames);
}

const char* storePathName(StorePath path) {
    return nameOf(path, kStorePathNames, "auto");
}

std::optional<StorePath> storePathFromName(std::string_view name) {
    return valueOf(name, kStorePathNames);
}

std::optional<ByDevice> byDeviceFromName(std::string_view name) {
    return valueOf(name, kByDeviceNames);
}

Status validateSparseOptions(const SolverOptions& o, uint32_t maxDimension,
                             uint32_t maxInvocations) {
    if (Status valid = validateOptions(o, maxDimension, maxInvocations); !valid) return valid;
    auto bad = [](const std::string& what) {
        return Status(Error{"the sparse domain cannot run " + what + " yet"});
    };
    const uint32_t cells[3] = {o.grid.cellsX, o.grid.cellsY, o.grid.cellsZ};
    for (int axis = 0; axis < 3; ++axis)
        if (cells[axis] % MFX_BRICK_SIZE != 0)
            return Error{"the sparse domain's cells along " + std::string(1, "xyz"[axis]) + " (" +
                         std::to_string(cells[axis]) + ") must be a multiple of " +
                         std::to_string(MFX_BRICK_SIZE) + ", the brick size"};
    if (o.pressureSolver != PressureSolver::Jacobi)
        return bad(std::string("the ") + pressureSolverName(o.pressureSolver) +
                   " pressure solver (it has jacobi)");
    if (o.advection != AdvectionScheme::SemiLagrangian)
        return bad(std::string(advectionName(o.advection)) + " advection (it has semi-lagrangian)");
    if (o.storage != Storage::Float32) return bad("fp16 storage (it has fp32)");
    if (o.vorticity != 0.0f) return bad("vorticity confinement (vorticity must be 0)");
    if (o.turbulence != 0.0f) return bad("turbulence (turbulence must be 0)");
    if (o.viscosity != 0.0f) return bad("viscosity (viscosity must be 0)");
    for (int axis = 0; axis < 3; ++axis)
        if (o.periodic(axis)) return bad(std::string("a periodic axis (") + "xyz"[axis] + ")");
    return Ok{};
}

Status validateEmitters(std::span<const shared::FluidEmitter> emitters) {
    for (size_t i = 0; i < emitters.size(); ++i) {
        const shared::FluidEmitter& e = emitters[i];
        const std::string where = "emitter " + std::to_string(i) + ": ";
        if (!finite(e.positionRadius)) return Error{where + "position or radius is not finite"};
        if (!finite(e.velocityStrength)) return Error{where + "velocity or strength is not finite"};
        if (!finite(e.pigment)) return Error{where + "pigment is not finite"};
        if (e.positionRadius.w <= 0.0f) return Error{where + "radius must be > 0"};
        if (e.velocityStrength.w < 0.0f) return Error{where + "strength must be >= 0"};
        if (e.pigment.x < 0.0f || e.pigment.y < 0.0f || e.pigment.z < 0.0f || e.pigment.w < 0.0f)
            return Error{where + "pigment components must be >= 0"};
    }
    return Ok{};
}

Status validateSolids(std::span<const shared::FluidSolid> solids) {
    for (size_t i = 0; i < solids.size(); ++i) {
        const shared::FluidSolid& s = solids[i];
        const std::string where = "solid " + std::to_string(i) + ": ";
        if (!finite(s.endA) || !finite(glm::vec3(s.endB)))
            return Error{where + "an end or the radius is not finite"};
        if (!finite(glm::vec3(s.velocityA)) || !finite(glm::vec3(s.velocityB)))
            return Error{where + "a velocity is not finite"};
        if (s.endA.w <= 0.0f) return Error{where + "radius must be > 0"};
    }
    return Ok{};
}

Status validateGpuSolids(std::span<const shared::FluidSolid> solids,
                         uint32_t maxUniformBufferRange) {
    if (Status valid = validateSolids(solids); !valid) return valid;
    if (solids.size() > kMaxGpuSolids)
        return Error{"solids: " + std::to_string(solids.size()) + " solids, at most " +
                     std::to_string(kMaxGpuSolids) + " a step"};
    const size_t bytes = kMaxGpuSolids * sizeof(shared::FluidSolid);
    if (!solids.empty() && maxUniformBufferRange < bytes)
        return Error{"solids: the device's uniform buffers hold " +
                     std::to_string(maxUniformBufferRange) + " bytes, solids need " +
                     std::to_string(bytes)};
    return Ok{};
}

Status validateSolidOptions(const SolverOptions& o) {
    if (o.pressureSolver != PressureSolver::Multigrid &&
        o.pressureSolver != PressureSolver::MultigridPcg)
        return Ok{};
    const bool halves = o.grid.cellsX >= 3 || o.grid.cellsY >= 3 || o.grid.cellsZ >= 3;
    if (o.multigrid.levels == 1 || !halves)
        return Error{std::string("solids: the pressure solver \"") +
                     pressureSolverName(o.pressureSolver) +
                     "\" takes solids only with two multigrid levels or more"};
    return Ok{};
}

shared::FluidParameters makeParameters(const SolverOptions& o, uint32_t emitterCount, double time) {
    shared::FluidParameters p{};
    p.size = glm::uvec4(o.grid.cellsX, o.grid.cellsY, o.grid.cellsZ, emitterCount);
    const float dt = o.substepDt();
    p.cell = glm::vec4(o.grid.cellSize, 1.0f / o.grid.cellSize, dt, o.drag);
    p.rates = glm::vec4(o.fade, o.buoyancy, o.vorticity,
                        o.viscosity * dt / (o.grid.cellSize * o.grid.cellSize));
    p.boundaryLow =
        glm::uvec4(uint32_t(o.boundaries[FaceLowX].kind), uint32_t(o.boundaries[FaceLowY].kind),
                   uint32_t(o.boundaries[FaceLowZ].kind), uint32_t(o.integrator));
    p.boundaryHigh =
        glm::uvec4(uint32_t(o.boundaries[FaceHighX].kind), uint32_t(o.boundaries[FaceHighY].kind),
                   uint32_t(o.boundaries[FaceHighZ].kind), 0u);
    for (int face = 0; face < 6; ++face)
        p.wallVelocity[face] = glm::vec4(o.boundaries[face].wallVelocity, 0.0f);
    p.turbulence = glm::vec4(o.turbulence, 1.0f / o.turbulenceScale,
                             float(time * double(o.turbulenceSpeed)), o.turbulenceScale);
    return p;
}

glm::uvec3 faceExtent(const GridShape& grid, int component) {
    return {grid.cellsX + (component == 0 ? 1u : 0u), grid.cellsY + (component == 1 ? 1u : 0u),
            grid.cellsZ + (component == 2 ? 1u : 0u)};
}

FieldState FieldState::zero(const GridShape& grid) {
    FieldState state;
    state.grid = grid;
    auto count = [](glm::uvec3 e) { return size_t(e.x) * e.y * e.z; };
    state.velocityX.assign(count(faceExtent(grid, 0)), 0.0f);
    state.velocityY.assign(count(faceExtent(grid, 1)), 0.0f);
    state.velocityZ.assign(count(faceExtent(grid, 2)), 0.0f);
    state.pressure.assign(grid.cellCount(), 0.0f);
    state.divergence.assign(grid.cellCount(), 0.0f);
    state.pigment.assign(grid.cellCount() * 4, 0.0f);
    return state;
}

} // namespace mfx::fluid
