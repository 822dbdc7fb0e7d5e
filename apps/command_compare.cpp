// motionfx compare: a scenario on the GPU solver and the CPU reference from the same input, the
// difference after every stage of every step.
#include "apps/commands.h"

#include "fluid/field_compare.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/scenarios.h"
#include "fluid/smoke_solver.h"

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

namespace mfx::app {

namespace {

struct StageRecord {
    uint32_t step;
    std::string stage;
    fluid::StateDifference difference;
};

nlohmann::json toJson(const fluid::Difference& d) {
    return {{"max_abs", d.maxAbs}, {"rel_l2", d.relL2}};
}

void printRecord(const StageRecord& r) {
    const fluid::StateDifference& d = r.difference;
    std::printf("%5u  %-22s %10.3e %10.3e  %10.3e %10.3e  %10.3e %10.3e  %10.3e %10.3e\n", r.step,
                r.stage.c_str(), d.velocity.maxAbs, d.velocity.relL2, d.pressure.maxAbs,
                d.pressure.relL2, d.pigment.maxAbs, d.pigment.relL2, d.divergence.maxAbs,
                d.divergence.relL2);
}

} // namespace

int runCompare(const cli::ParsedArgs& parsed) {
    if (parsed.positional.empty()) {
        printError("compare needs a scenario: one of " + scenarioNameList() + " (see --help)");
        return kExitUsage;
    }

    auto steps = cli::parseUnsigned(parsed.value("steps", "20"), 1, 100000, "--steps");
    auto grid = cli::parseGrid(parsed.value("grid", "32x32x32"), 1024);
    Result<double> tolerance = 0.0;
    if (parsed.has("tolerance"))
        tolerance = cli::parseNumber(parsed.value("tolerance"), 0.0, 1e30, "--tolerance");
    if (reportFirstError(steps, grid, tolerance)) return kExitUsage;
    std::optional<fluid::Stage> onlyStage;
    if (parsed.has("stage")) {
        onlyStage = fluid::stageFromName(parsed.value("stage"));
        if (!onlyStage) {
            printError("no stage \"" + parsed.value("stage") +
                       "\"; stages are: " + stageNameList());
            return kExitUsage;
        }
    }
    const std::array<uint32_t, 3> cells = grid.value();
    auto scenario =
        fluid::makeScenario(parsed.positional[0], glm::uvec3(cells[0], cells[1], cells[2]));
    if (!scenario) {
        printError(scenario.error().message);
        return kExitUsage;
    }
    if (parsed.has("pressure")) {
        const auto pressure = fluid::pressureSolverFromName(parsed.value("pressure"));
        if (!pressure) {
            printError("--pressure: no pressure solver \"" + parsed.value("pressure") +
                       "\"; solvers are jacobi, rbgs, multigrid, mgpcg");
            return kExitUsage;
        }
        scenario.value().options.pressureSolver = *pressure;
    }
    const std::string jsonPath = parsed.value("json");
    std::ofstream jsonFile;
    if (!openOutputFile(jsonPath, jsonFile)) return kExitFailure;

    const std::unique_ptr<gpu::Context> context = createContext(parsed);
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    const fluid::Scenario& s = scenario.value();
    auto gpuSolver = fluid::SmokeSolver::create(ctx, s.options);
    if (!gpuSolver) {
        printError(gpuSolver.error().message);
        return kExitFailure;
    }
    fluid::SmokeSolver& gpu = *gpuSolver.value();
    fluid::ReferenceSolver cpu(s.options);
    gpu.setState(s.initial);
    cpu.setState(s.initial);

    std::printf("device    %s\nscenario  %s: %s\ngrid      %ux%ux%u, %u steps, %s pressure "
                "solve, %s\n\n",
                ctx.info().name.c_str(), s.name.c_str(), s.description.c_str(), cells[0], cells[1],
                cells[2], steps.value(), fluid::pressureSolverName(s.options.pressureSolver),
                onlyStage ? ("stage " + std::string(fluid::stageName(*onlyStage)) +
                             " alone, from the reference's state at each step")
                                .c_str()
                          : "whole steps, both solvers evolving on their own");
    std::printf("%5s  %-22s %21s  %21s  %21s  %21s\n", "", "", "velocity", "pressure", "pigment",
                "divergence");
    std::printf("%5s  %-22s %10s %10s  %10s %10s  %10s %10s  %10s %10s\n", "step", "stage",
                "max|d|", "rel L2", "max|d|", "rel L2", "max|d|", "rel L2", "max|d|", "rel L2");

    std::vector<StageRecord> records;
    StageRecord worst{0, "", {}};
    double worstRelL2 = 0.0;
    auto record = [&](uint32_t step, fluid::Stage stage) {
        StageRecord r{step, fluid::stageName(stage), fluid::difference(gpu.state(), cpu.state())};
        printRecord(r);
        if (r.difference.maxRelL2() > worstRelL2 || records.empty()) {
            worstRelL2 = r.difference.maxRelL2();
            worst = r;
        }
        records.push_back(std::move(r));
    };
    for (uint32_t step = 0; step < steps.value(); ++step) {
        const std::vector<shared::FluidEmitter> emitters = s.emitters(step);
        if (Status ok = gpu.setEmitters(emitters); !ok) {
            printError(ok.error().message);
            return kExitFailure;
        }
        if (onlyStage) {
            const fluid::FieldState input = cpu.state();
            gpu.setState(input);
            gpu.runStage(*onlyStage);
            cpu.runStage(*onlyStage, emitters);
            record(step, *onlyStage);
            cpu.setState(input);
            cpu.step(emitters);
            continue;
        }
        for (uint32_t substep = 0; substep < s.options.substeps; ++substep)
            for (fluid::Stage stage : fluid::stepOrder()) {
                gpu.runStage(stage);
                cpu.runStage(stage, emitters);
                record(step, stage);
            }
    }
    std::printf("\nlargest relative L2 difference: %.3e (%s, step %u)\n", worstRelL2,
                worst.stage.c_str(), worst.step);

    if (jsonFile.is_open()) {
        nlohmann::json stages = nlohmann::json::array();
        for (const StageRecord& r : records)
            stages.push_back({{"step", r.step},
                              {"stage", r.stage},
                              {"velocity", toJson(r.difference.velocity)},
                              {"pressure", toJson(r.difference.pressure)},
                              {"divergence", toJson(r.difference.divergence)},
                              {"pigment", toJson(r.difference.pigment)}});
        const nlohmann::json document = {
            {"device", ctx.info().name},
            {"scenario", s.name},
            {"grid", {cells[0], cells[1], cells[2]}},
            {"steps", steps.value()},
            {"pressure", fluid::pressureSolverName(s.options.pressureSolver)},
            {"mode", onlyStage ? "stage" : "step"},
            {"stage_alone", onlyStage ? fluid::stageName(*onlyStage) : ""},
            {"stages", stages},
            {"max_rel_l2", worstRelL2}};
        jsonFile << document.dump(2) << "\n";
        if (!jsonFile) {
            printError("cannot write " + jsonPath);
            return kExitFailure;
        }
    }
    if (parsed.has("tolerance") && worstRelL2 > tolerance.value()) {
        printError("relative L2 difference " + std::to_string(worstRelL2) +
                   " exceeds the tolerance " + parsed.value("tolerance"));
        return kExitFailure;
    }
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
