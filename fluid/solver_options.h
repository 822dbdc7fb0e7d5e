// What a smoke simulation is asked to do: grid, time step, stage parameters and boundaries (the
// stages themselves: fluid/stage_table.h). The discretisation behind each
// option is written down in docs/fluid.md.
#pragma once

#include "core/result.h"
#include "fluid/grid.h"
#include "fluid/stage_table.h"
#include "shaders/shared/fluid.h"

#include <array>
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mfx::fluid {

enum class Boundary {
    WallFreeSlip = MFX_BOUNDARY_WALL_FREE_SLIP, // no flow through; tangential flow slides freely
    WallNoSlip = MFX_BOUNDARY_WALL_NO_SLIP,     // no flow through; tangential flow = wall velocity
    Open = MFX_BOUNDARY_OPEN,                   // outflow: pressure 0 outside, zero gradient
    Periodic = MFX_BOUNDARY_PERIODIC, // wraps to the opposite face (both faces of an axis)
};

enum class Integrator { Euler = MFX_INTEGRATOR_EULER, RK2 = MFX_INTEGRATOR_RK2 };

// How the pressure Poisson equation is solved (docs/fluid.md, "Accuracy options").
enum class PressureSolver {
    Jacobi,              // jacobiIterations sweeps
    RedBlackGaussSeidel, // jacobiIterations sweeps, each the red cells then the black ones
    Multigrid,           // multigrid.cycles V-cycles
    MultigridPcg,        // conjugate gradient preconditioned by one V-cycle per iteration
};

// How velocity and pigment are advected.
enum class AdvectionScheme {
    SemiLagrangian, // one back-trace and a trilinear sample
    MacCormack,     // forward and backward semi-Lagrangian steps, the error corrected, limited
    Bfecc,          // back and forth error compensation and correction, limited
};

// How the fields are stored between stages: 32-bit floats, or 16-bit (arithmetic in 32 bits).
enum class Storage { Float32, Float16 };

// How a stage that rewrites a whole field stores it (a performance setting only: the results are
// the same bit for bit; docs/fluid.md, "Grid"). Buffer: into a storage buffer, then copied into
// the field's image (a CPU driver's image stores are slow, its copies cheap). Direct: straight into
// the image (a GPU, where the copy would move every byte twice more). Auto: Buffer on a CPU
// device, Direct on any other.
enum class StorePath { Auto, Buffer, Direct };

// A choice the device makes unless told.
enum class ByDevice { Auto, Off, On };

struct MultigridOptions {
    uint32_t levels = 0;     // grids in the hierarchy, the finest included (0: as many as halve
                             // every axis down to at least 2 cells)
    uint32_t preSmooth = 2;  // red-black Gauss-Seidel sweeps before restriction, per level
    uint32_t postSmooth = 2; // ... after prolongation
    uint32_t cycles = 2;     // V-cycles (PressureSolver::Multigrid)
    // Invocations of the one workgroup that cycles the coarse levels (cycle_coarse_levels.comp);
    // 0: by device, 8 on a CPU device (a barrier costs the more there, the more invocations wait
    // at it), 64 on a GPU (one per brick of the finest level it takes: with fewer, each phase's
    // loads are serialised in a handful of threads). The result does not depend on it.
    uint32_t coarseGroup = 0;
    // Rows (y) and layers (z) of the brick one invocation relaxes, restricts or prolongs (1, 2
    // or 4; its x extent is one vec4 of cells); 0: by device, 4 on a CPU device (a row loaded
    // serves several cells, and fewer invocations pay a CPU driver's per-invocation cost), 1 on a
    // GPU (16 times the invocations: every dispatch of a 64³ level fills the chip). The levels
    // of 16³ cells and below are cycled in one workgroup either way. The result does not depend
    // on it.
    uint32_t brick = 0;
    // The largest level, in cells, whose V-cycle runs in the one workgroup of
    // cycle_coarse_levels.comp (it and every coarser level; the levels above are dispatched one
    // operation at a time); 0: 4,096 (16³). At most 4,096: lavapipe ends an invocation's loops
    // after 65,535 iterations in all. The result does not depend on it.
    uint32_t coarseCells = 0;
    // The multigrid solver's restriction (R0) computes the residual it restricts, instead of a
    // pass that writes it before: one dispatch and a write and a read of the residual fewer per
    // level, for a stencil whose sums scatter into the coarse brick. Auto: on a GPU only (on
    // lavapipe it made the solve 1.18 times slower at 96³). MGPCG's P^T keeps the pass.
    ByDevice residualInRestriction = ByDevice::Auto;
};

// Names as the command line and the benchmarks spell them ("jacobi", "rbgs", "multigrid",
// "mgpcg"; "semi-lagrangian", "maccormack", "bfecc"; "fp32", "fp16").
const char* pressureSolverName(PressureSolver solver);
std::optional<PressureSolver> pressureSolverFromName(std::string_view name);
const char* advectionName(AdvectionScheme scheme);
std::optional<AdvectionScheme> advectionFromName(std::string_view name);
const char* storageName(Storage storage);
std::optional<Storage> storageFromName(std::string_view name);
const char* storePathName(StorePath path); // "auto", "buffer", "direct"
std::optional<StorePath> storePathFromName(std::string_view name);
std::optional<ByDevice> byDeviceFromName(std::string_view name); // "auto", "off", "on"

// Domain faces in the order -x, +x, -y, +y, -z, +z.
enum Face { FaceLowX = 0, FaceHighX, FaceLowY, FaceHighY, FaceLowZ, FaceHighZ };

struct FaceBoundary {
    Boundary kind = Boundary::WallFreeSlip;
    // Velocity of a wall. Walls never move along their own normal (that component is ignored);
    // a no-slip wall drags tangential flow towards the other components.
    glm::vec3 wallVelocity{0.0f};
};

struct SolverOptions {
    GridShape grid;
    float dt = 1.0f / 60.0f; // seconds per step
    uint32_t substeps = 1;   // each step runs every stage this many times with dt/substeps
    Integrator integrator = Integrator::Euler;
    float fade = 0.0f;      // pigment decay rate per second: pigment *= exp(-fade*dt)
    float drag = 0.0f;      // velocity decay rate per second: u *= exp(-drag*dt)
    float buoyancy = 0.0f;  // upward acceleration per unit pigment alpha (0 = off)
    float vorticity = 0.0f; // vorticity confinement strength epsilon (0 = off)
    // Curl-noise turbulence (docs/fluid.md, "applyTurbulence"): a divergence-free acceleration
    // of `turbulence` world units per second^2 (0 = off), its features `turbulenceScale` world
    // units across, changing `turbulenceSpeed` times a second.
    float turbulence = 0.0f;
    float turbulenceScale = 0.25f;
    float turbulenceSpeed = 1.0f;
    float viscosity = 0.0f;            // kinematic viscosity nu, world units^2 per second (0 = off)
    uint32_t viscosityIterations = 20; // Jacobi sweeps of the implicit diffusion solve
    PressureSolver pressureSolver = PressureSolver::Jacobi;
    uint32_t jacobiIterations = 20; // sweeps of the pressure solve (Jacobi and red-black)
    MultigridOptions multigrid;
    float cgTolerance = 1e-3f;     // MultigridPcg: stop at this relative residual ...
    uint32_t cgMaxIterations = 20; // ... or after this many iterations
    bool warmStart = false;        // start the pressure solve from the last step's pressure
    // A step whose Jacobi solve starts cold computes its first sweep in the divergence pass (the
    // sweep needs each cell's own divergence only): one dispatch, its barrier and a read of the
    // divergence fewer, the same values. Auto: on every device (a performance setting only).
    ByDevice firstSweepInDivergence = ByDevice::Auto;
    // With solids, the stages that read them dispatched twice: over the workgroup blocks away
    // from solids with every solid test compiled out, and over those near them (the block lists
    // mark_solids builds; shaders/fluid/fluid_solids.glsl). The same values. Auto: on CPU
    // devices, whose compiled branches run both sides; a GPU skips a workgroup's untaken
    // branch by itself (a performance setting only).
    ByDevice solidLists = ByDevice::Auto;
    AdvectionScheme advection = AdvectionScheme::SemiLagrangian;
    Storage storage = Storage::Float32;
    std::array<FaceBoundary, 6> boundaries{};
    // Workgroup shape of every compute dispatch (a performance setting only: results do not
    // depend on it). At most the device's maxComputeWorkGroupInvocations in all.
    std::array<uint32_t, 3> workgroup{MFX_FLUID_GROUP_X, MFX_FLUID_GROUP_Y, MFX_FLUID_GROUP_Z};
    StorePath storePath = StorePath::Auto; // a performance setting only, as the workgroup

    float substepDt() const { return dt / float(substeps); }
    // Whether a step computes the pressure solve's first sweep in the divergence pass.
    bool firstSweepFused() const {
        return pressureSolver == PressureSolver::Jacobi && !warmStart && jacobiIterations > 0 &&
               firstSweepInDivergence != ByDevice::Off;
    }
    bool periodic(int axis) const { return boundaries[2 * axis].kind == Boundary::Periodic; }
};

// Checks every option: finite, in range, periodic faces paired. The error names the option.
Status validateOptions(const SolverOptions& options, uint32_t maxDimension = 4096,
                       uint32_t maxInvocations = 1024);

// What the sparse domain (fluid/sparse_smoke_solver.h, docs/fluid.md "Sparse domain") can run:
// valid options whose grid is a whole number of bricks (8 cells) along every axis, with Jacobi
// pressure, semi-Lagrangian advection, fp32 storage, no vorticity confinement, no viscosity and
// no periodic axis. The error names the first option it cannot run.
Status validateSparseOptions(const SolverOptions& options, uint32_t maxDimension = 4096,
                             uint32_t maxInvocations = 1024);

// Refuses emitters with NaN/Inf, a radius <= 0, a negative strength or negative pigment; the
// error names the emitter index and the field.
Status validateEmitters(std::span<const shared::FluidEmitter> emitters);
// Every solid's ends, radius and velocities finite, its radius > 0; the error names the solid.
Status validateSolids(std::span<const shared::FluidSolid> solids);
// The most solids a GPU solver takes a step: they travel in the command buffer (vkCmdUpdateBuffer's
// 64 KiB) into a uniform buffer the shaders index (shaders/fluid/mark_solids.comp's 1024).
inline constexpr size_t kMaxGpuSolids = 65536 / sizeof(shared::FluidSolid);
// validateSolids, at most kMaxGpuSolids, and uniform buffers of `maxUniformBufferRange` bytes
// that hold them.
Status validateGpuSolids(std::span<const shared::FluidSolid> solids,
                         uint32_t maxUniformBufferRange);
// Whether a dense solver with `options` takes solids: every pressure solver does, multigrid and
// MGPCG only with a hierarchy of two levels or more (their coarse levels do not see the solids,
// so the simulation grid cannot be the coarsest; docs/fluid.md, "Solids").
Status validateSolidOptions(const SolverOptions& options);

// The uniform block of the sub-steps of a step starting at `time` (seconds of simulation: the
// turbulence's noise time).
shared::FluidParameters makeParameters(const SolverOptions& options, uint32_t emitterCount,
                                       double time = 0.0);

// Every field of a simulation, as plain floats (x fastest): the exchange format between the GPU
// solver, the CPU reference and the tests.
struct FieldState {
    GridShape grid;
    std::vector<float> velocityX;  // (nx+1) * ny * nz faces
    std::vector<float> velocityY;  // nx * (ny+1) * nz faces
    std::vector<float> velocityZ;  // nx * ny * (nz+1) faces
    std::vector<float> pressure;   // nx * ny * nz cells
    std::vector<float> divergence; // nx * ny * nz cells
    std::vector<float> pigment;    // nx * ny * nz cells, RGBA interleaved

    static FieldState zero(const GridShape& grid);
};

// Faces along each axis of velocity component `component` (0 x, 1 y, 2 z).
glm::uvec3 faceExtent(const GridShape& grid, int component);

} // namespace mfx::fluid
