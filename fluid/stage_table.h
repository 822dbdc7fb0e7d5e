// The stages of the smoke solver, each named once: one table (fluid/stage_table.cpp) gives each
// stage its name, its GPU programs (shaders/fluid/<kernel>.comp, and sparse_<stage>.comp on the
// sparse domain), the member functions that record it on the dense and the sparse solver, its CPU
// reference twin (fluid/reference/<stage>.cpp) and the bytes it must move: the model the
// benchmarks measure achieved bandwidth against. The dense solver, the sparse solver, the
// reference, the comparisons and the benchmarks all walk this table.
//
// Adding a stage: its shader(s) in shaders/fluid/, its reference file in fluid/reference/, its
// recording functions on SmokeSolver (and SparseSmokeSolver, or null where the sparse domain
// refuses the option that turns it on), its enum value below, and one entry in the table, placed
// where it runs in the sub-step (docs/architecture.md, "Adding a solver stage").
//
// applyBoundaries runs alone only (runStage: a state set from outside made to obey the
// boundaries), not in a step: the stages that write faces keep them as the boundaries want them
// (wall-normal faces 0; advectVelocity computes a periodic axis's last face as its first, and the
// later stages and the projection keep the two equal), so the boundary pass a step once ran before
// the divergence and after the projection changed nothing (tests/test_fluid_stages.cpp,
// AStepLeavesTheFacesAsTheBoundariesWantThem).
#pragma once

#include "shaders/shared/fluid.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>
#include <vulkan/vulkan.h>

namespace mfx::fluid {

class SmokeSolver;
class SparseSmokeSolver;
class ReferenceSolver;
struct SolverOptions;

// The table's keys, in the order the table lists them (stage_table.cpp asserts one entry per
// value; tests/test_stage_table.cpp checks the order).
enum class Stage {
    MarkSolids,
    SplatImpulses,
    AdvectVelocity,
    AdvectPigment,
    ApplyBuoyancy,
    VorticityConfinement,
    ApplyTurbulence,
    DiffuseViscosity,
    ApplyBoundaries,
    ComputeDivergence,
    SolvePressure,
    Project,
};
inline constexpr size_t kStageCount = 12;

// Bytes a stage must move in one sub-step: every field it reads read once and every field it
// writes written once (what a kernel that fuses the stage's passes and keeps neighbours in caches
// moves; copies, scratch buffers and re-reads are the implementation's overhead, not the model's).
struct StageBytes {
    double read = 0.0;
    double written = 0.0;
    double total() const { return read + written; }
};

// What a bytes model needs beyond the options: the cells the emitters' boxes cover this sub-step
// (the splat touches only those; the benchmark computes them from its emitters).
struct StageWork {
    uint64_t splatCells = 0;
    // The iterations the pressure solve ran (MGPCG stops on its tolerance); 0: the options' most.
    uint32_t pressureIterations = 0;
    // The solids a sub-step marks (0: markSolids records nothing).
    uint32_t solids = 0;
};

using Emitters = std::span<const shared::FluidEmitter>;

struct StageEntry {
    Stage stage;
    const char* name;          // the stage's passes and reports, e.g. "advect_velocity"
    const char* kernels;       // its dense GPU programs, space-separated (shaders/fluid/*.comp)
    const char* sparseKernels; // on the sparse domain ("" where the sparse domain does not run it)
    void (SmokeSolver::*dense)(VkCommandBuffer);
    void (SparseSmokeSolver::*sparse)(VkCommandBuffer); // null: not run on the sparse domain
    void (*reference)(ReferenceSolver&, Emitters);
    StageBytes (*bytes)(const SolverOptions&, const StageWork&);
    const char* bytesModel; // the model in words, per cell or face
    bool inStep;            // runs in a sub-step (else only alone: runStage)
};

// Every stage, in the order a sub-step runs those it runs, each once.
std::span<const StageEntry> stageTable();
const StageEntry& stageEntry(Stage stage);

// The stages of the table in order, and those a sub-step runs (inStep), in its order.
const std::vector<Stage>& allStages();
const std::vector<Stage>& stepOrder();

// "splat_impulses", "advect_velocity", ...
const char* stageName(Stage stage);
std::optional<Stage> stageFromName(std::string_view name);

// The bytes one whole sub-step must move: every stage of stepOrder().
StageBytes stepBytes(const SolverOptions& options, const StageWork& work);

} // namespace mfx::fluid
