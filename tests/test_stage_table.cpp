// The stage table (fluid/stage_table.h): every stage named once, in the enum's order, with
// programs that exist, a reference twin, and a bytes model that answers to its options.
#include "fluid/solver_options.h"
#include "fluid/stage_table.h"
#include "shaders/embedded.h"

#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>

namespace mfx::test {
namespace {

std::vector<std::string> words(const char* list) {
    std::vector<std::string> out;
    std::stringstream stream(list);
    for (std::string word; stream >> word;)
        out.push_back(word);
    return out;
}

std::set<std::string> embeddedComputeShaders() {
    std::set<std::string> names;
    for (const shaders::EmbeddedShader& shader : shaders::allShaders())
        names.insert(shader.fileName);
    return names;
}

TEST(StageTable, ListsTheStagesInTheEnumsOrder) {
    const auto table = fluid::stageTable();
    ASSERT_EQ(table.size(), fluid::kStageCount);
    for (size_t i = 0; i < table.size(); ++i) {
        EXPECT_EQ(table[i].stage, fluid::Stage(i)) << table[i].name;
        EXPECT_EQ(&fluid::stageEntry(fluid::Stage(i)), &table[i]);
    }
}

TEST(StageTable, NamesAreUniqueAndRoundTrip) {
    std::set<std::string> seen;
    for (fluid::Stage stage : fluid::allStages()) {
        const char* name = fluid::stageName(stage);
        EXPECT_TRUE(seen.insert(name).second) << name;
        EXPECT_EQ(fluid::stageFromName(name), stage) << name;
    }
    EXPECT_FALSE(fluid::stageFromName("no_such_stage").has_value());
}

TEST(StageTable, StepOrderRunsTheStagesInTheStepInTheTablesOrder) {
    // applyBoundaries runs alone only: the other stages keep the faces as it would leave them.
    const std::vector<fluid::Stage> expected = {fluid::Stage::MarkSolids,
                                                fluid::Stage::SplatImpulses,
                                                fluid::Stage::AdvectVelocity,
                                                fluid::Stage::AdvectPigment,
                                                fluid::Stage::ApplyBuoyancy,
                                                fluid::Stage::VorticityConfinement,
                                                fluid::Stage::ApplyTurbulence,
                                                fluid::Stage::DiffuseViscosity,
                                                fluid::Stage::ComputeDivergence,
                                                fluid::Stage::SolvePressure,
                                                fluid::Stage::Project};
    EXPECT_EQ(fluid::stepOrder(), expected);
    EXPECT_EQ(fluid::allStages().size(), fluid::kStageCount);
}

TEST(StageTable, EveryEntryHasItsFunctionsAndProgramsThatExist) {
    const std::set<std::string> shaders = embeddedComputeShaders();
    for (const fluid::StageEntry& entry : fluid::stageTable()) {
        EXPECT_NE(entry.dense, nullptr) << entry.name;
        EXPECT_NE(entry.reference, nullptr) << entry.name;
        EXPECT_NE(entry.bytes, nullptr) << entry.name;
        EXPECT_GT(std::string(entry.bytesModel).size(), 10u) << entry.name;
        const auto dense = words(entry.kernels);
        EXPECT_FALSE(dense.empty()) << entry.name;
        for (const std::string& kernel : dense)
            EXPECT_TRUE(shaders.count(kernel + ".comp")) << entry.name << ": " << kernel;
        // A stage the sparse domain runs has both its function and its programs; one it does not
        // run has neither.
        const auto sparse = words(entry.sparseKernels);
        EXPECT_EQ(entry.sparse != nullptr, !sparse.empty()) << entry.name;
        for (const std::string& kernel : sparse)
            EXPECT_TRUE(shaders.count(kernel + ".comp")) << entry.name << ": " << kernel;
    }
}

fluid::SolverOptions optionsOf(uint32_t n) {
    fluid::SolverOptions o;
    o.grid = {n, n, n, 0.1f};
    return o;
}

TEST(StageTable, BytesModelsCountFieldsReadAndWritten) {
    const fluid::SolverOptions o = optionsOf(32);
    const double cells = 32.0 * 32 * 32, faces = 3.0 * 33 * 32 * 32;
    const auto bytes = [&](fluid::Stage stage, const fluid::SolverOptions& options) {
        return fluid::stageEntry(stage).bytes(options, {});
    };
    // Projection: velocity and pressure read, velocity written, four bytes each.
    EXPECT_DOUBLE_EQ(bytes(fluid::Stage::Project, o).read, 4.0 * (faces + cells));
    EXPECT_DOUBLE_EQ(bytes(fluid::Stage::Project, o).written, 4.0 * faces);
    // Twenty Jacobi sweeps, cold: each reads pressure and divergence and writes pressure, but the
    // first reads no pressure (it is 0). By default the divergence pass does that first sweep:
    // it writes its pressure, and the solve runs the other 19.
    fluid::SolverOptions apart = o;
    apart.firstSweepInDivergence = fluid::ByDevice::Off;
    EXPECT_DOUBLE_EQ(bytes(fluid::Stage::SolvePressure, apart).total(), 4.0 * cells * (20 * 3 - 1));
    EXPECT_DOUBLE_EQ(bytes(fluid::Stage::ComputeDivergence, apart).total(), 4.0 * (faces + cells));
    EXPECT_DOUBLE_EQ(bytes(fluid::Stage::SolvePressure, o).total(), 4.0 * cells * 19 * 3);
    EXPECT_DOUBLE_EQ(bytes(fluid::Stage::ComputeDivergence, o).total(), 4.0 * (faces + 2 * cells));
    // Fused, the pair moves a read of the divergence less.
    EXPECT_DOUBLE_EQ(fluid::stepBytes(apart, {}).total() - fluid::stepBytes(o, {}).total(),
                     4.0 * cells);
    // Half the bytes in fp16.
    fluid::SolverOptions half = o;
    half.storage = fluid::Storage::Float16;
    EXPECT_DOUBLE_EQ(bytes(fluid::Stage::Project, half).total(),
                     0.5 * bytes(fluid::Stage::Project, o).total());
    // A stage whose option is off moves nothing; on, it moves the velocity twice.
    EXPECT_EQ(bytes(fluid::Stage::VorticityConfinement, o).total(), 0.0);
    fluid::SolverOptions vortical = o;
    vortical.vorticity = 1.0f;
    EXPECT_DOUBLE_EQ(bytes(fluid::Stage::VorticityConfinement, vortical).total(), 8.0 * faces);
    // The splat moves the emitters' boxes only.
    EXPECT_EQ(bytes(fluid::Stage::SplatImpulses, o).total(), 0.0);
    EXPECT_DOUBLE_EQ(fluid::stageEntry(fluid::Stage::SplatImpulses).bytes(o, {1000}).total(),
                     4.0 * 14 * 1000);
    // The step is the sum over the step order.
    double sum = 0.0;
    for (fluid::Stage stage : fluid::stepOrder())
        sum += bytes(stage, o).total();
    EXPECT_DOUBLE_EQ(fluid::stepBytes(o, {}).total(), sum);
    // Costlier schemes and solvers move more.
    fluid::SolverOptions bfecc = o;
    bfecc.advection = fluid::AdvectionScheme::Bfecc;
    EXPECT_GT(bytes(fluid::Stage::AdvectVelocity, bfecc).total(),
              2.5 * bytes(fluid::Stage::AdvectVelocity, o).total());
    fluid::SolverOptions multigrid = o;
    multigrid.pressureSolver = fluid::PressureSolver::Multigrid;
    multigrid.multigrid.cycles = 1;
    const double cycle = bytes(fluid::Stage::SolvePressure, multigrid).total();
    // One V-cycle with 2 + 2 smoothing sweeps moves 18.25 N values on the finest level
    // (smoothing 12, residual 3, restriction 1.125, prolongation 2.125), the coarser levels at
    // most a seventh more; the solve also reads the divergence and writes the pressure (2 N).
    EXPECT_GT(cycle, 4.0 * cells * (18.25 + 2.0));
    EXPECT_LT(cycle, 4.0 * cells * (18.25 * 8.0 / 7.0 + 2.0));
}

} // namespace
} // namespace mfx::test
