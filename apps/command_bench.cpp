// motionfx bench: benchmark programs that print tables (never pass/fail on time).
//   motionfx bench solver       GPU milliseconds per solver stage and per step, by grid size.
//   motionfx bench trajectory   split trajectory against the unsplit baseline, by lifetime
//                               (command_bench_trajectory.cpp).
#include "apps/commands.h"

#include "core/gpu/commands.h"
#include "core/gpu/timer.h"
#include "fluid/scenarios.h"
#include "fluid/smoke_solver.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

namespace mfx::app {

namespace {

struct GridResult {
    std::array<uint32_t, 3> grid;
    std::array<uint32_t, 3> workgroup;
    double stepMs = 0.0;                   // median GPU time of a whole step (sum of its stages)
    double wallMs = 0.0;                   // median CPU wall time of record + submit + wait
    std::map<std::string, double> stageMs; // median per stage
};

Result<std::vector<std::array<uint32_t, 3>>> parseGridList(const std::string& text) {
    std::vector<std::array<uint32_t, 3>> grids;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        if (item.find('x') == std::string::npos) item = item + "x" + item + "x" + item;
        auto grid = cli::parseGrid(item, 1024);
        if (!grid) return Error{"--grids: " + grid.error().message};
        grids.push_back(grid.value());
    }
    if (grids.empty()) return Error{"--grids needs at least one grid, e.g. 32,64 or 96x64x48"};
    return grids;
}

Result<std::vector<std::array<uint32_t, 3>>> parseWorkgroupList(const std::string& text) {
    std::vector<std::array<uint32_t, 3>> shapes;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        auto shape = cli::parseGrid(item, 1024);
        if (!shape)
            return Error{"--workgroups: '" + item + "' is not of the form XxYxZ, e.g. 8x8x4"};
        shapes.push_back(shape.value());
    }
    if (shapes.empty()) return Error{"--workgroups needs at least one shape, e.g. 8x8x4,32x4x2"};
    return shapes;
}

std::string shapeLabel(const std::array<uint32_t, 3>& s) {
    return std::to_string(s[0]) + "x" + std::to_string(s[1]) + "x" + std::to_string(s[2]);
}

// Times one grid with one workgroup shape: the median of `steps` steps after 3 warm-up steps.
Result<GridResult> benchGrid(const gpu::Context& ctx, const std::string& scenarioName,
                             std::array<uint32_t, 3> cells, std::array<uint32_t, 3> workgroup,
                             uint32_t jacobi, fluid::PressureSolver pressure, uint32_t steps) {
    fluid::Scenario scenario =
        fluid::makeScenario(scenarioName, glm::uvec3(cells[0], cells[1], cells[2])).value();
    scenario.options.jacobiIterations = jacobi;
    scenario.options.pressureSolver = pressure;
    scenario.options.workgroup = workgroup;
    auto solverResult = fluid::SmokeSolver::create(ctx, scenario.options);
    if (!solverResult) return solverResult.error();
    fluid::SmokeSolver& solver = *solverResult.value();
    solver.setState(scenario.initial);
    gpu::GpuTimer timer(ctx, solver.passesPerStep());
    std::vector<double> stepTimes, wallTimes;
    std::map<std::string, std::vector<double>> stageTimes;
    std::fprintf(stderr, "  %ux%ux%u, workgroup %s ", cells[0], cells[1], cells[2],
                 shapeLabel(workgroup).c_str());
    const uint32_t warmup = 3;
    for (uint32_t step = 0; step < warmup + steps; ++step) {
        // Emitters stay on (the scenario's first step) so every stage has work each step.
        if (Status ok = solver.setEmitters(scenario.emitters(0)); !ok) return ok.error();
        const auto start = std::chrono::steady_clock::now();
        gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
            timer.reset(cmd);
            solver.recordStep(cmd, &timer);
        });
        const double wall =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        std::fputc('.', stderr);
        if (step < warmup) continue;
        std::map<std::string, double> perStage;
        double total = 0.0;
        for (const gpu::PassTime& pass : timer.results()) {
            perStage[pass.name] += pass.milliseconds;
            total += pass.milliseconds;
        }
        for (const auto& [name, ms] : perStage)
            stageTimes[name].push_back(ms);
        stepTimes.push_back(total);
        wallTimes.push_back(wall);
    }
    std::fputc('\n', stderr);
    GridResult r{cells, workgroup, median(stepTimes), median(wallTimes), {}};
    for (const auto& [name, times] : stageTimes)
        r.stageMs[name] = median(times);
    return r;
}

} // namespace

int runBenchSolver(const cli::ParsedArgs& parsed) {
    const std::string domain = parsed.value("domain", "dense");
    if (domain == "sparse") return runBenchSparse(parsed);
    if (domain != "dense") {
        printError("--domain must be dense or sparse, not \"" + domain + "\"");
        return kExitUsage;
    }
    for (const char* sparseOnly : {"virtual", "bricks", "plot"})
        if (parsed.has(sparseOnly)) {
            printError(std::string("--") + sparseOnly + " is an option of --domain sparse");
            return kExitUsage;
        }
    auto grids = parseGridList(parsed.value("grids", "32,64,96,128"));
    auto jacobi = cli::parseUnsigned(parsed.value("jacobi", "20"), 0, 100000, "--jacobi");
    auto steps = cli::parseUnsigned(parsed.value("steps", "10"), 1, 10000, "--steps");
    auto workgroups = parseWorkgroupList(
        parsed.value("workgroups", shapeLabel(fluid::SolverOptions{}.workgroup)));
    if (reportFirstError(grids, jacobi, steps, workgroups)) return kExitUsage;
    const auto pressure = fluid::pressureSolverFromName(parsed.value("pressure", "jacobi"));
    if (!pressure) {
        printError("--pressure: no pressure solver \"" + parsed.value("pressure") +
                   "\"; solvers are jacobi, rbgs, multigrid, mgpcg");
        return kExitUsage;
    }
    const std::string scenarioName = parsed.value("scenario", "puff");
    if (!fluid::makeScenario(scenarioName, {2, 2, 2})) {
        printError(fluid::makeScenario(scenarioName, {2, 2, 2}).error().message);
        return kExitUsage;
    }
    const std::string jsonPath = parsed.value("json");
    std::ofstream jsonFile;
    if (!openOutputFile(jsonPath, jsonFile)) return kExitFailure;

    const std::unique_ptr<gpu::Context> context = createTimingContext(parsed, "the solver");
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    std::printf("smoke solver benchmark on %s (%s)\nscenario %s, pressure solver %s, %u Jacobi "
                "sweeps, median of %u steps after 3 warm-up steps; GPU milliseconds from "
                "timestamp queries\n\n",
                ctx.info().name.c_str(), ctx.info().driverInfo.c_str(), scenarioName.c_str(),
                fluid::pressureSolverName(*pressure), jacobi.value(), steps.value());

    std::vector<GridResult> results;
    for (const auto& cells : grids.value())
        for (const auto& workgroup : workgroups.value()) {
            auto r = benchGrid(ctx, scenarioName, cells, workgroup, jacobi.value(), *pressure,
                               steps.value());
            if (!r) {
                printError(r.error().message);
                return kExitFailure;
            }
            results.push_back(std::move(r.value()));
        }

    // Table: one row per stage (in step order), one column per grid (and workgroup shape).
    const bool shapes = workgroups.value().size() > 1;
    std::printf("%-24s", "stage (ms)");
    for (const GridResult& r : results)
        std::printf(" %12s", shapeLabel(r.grid).c_str());
    std::printf("\n");
    if (shapes) {
        std::printf("%-24s", "workgroup");
        for (const GridResult& r : results)
            std::printf(" %12s", shapeLabel(r.workgroup).c_str());
        std::printf("\n");
    }
    for (fluid::Stage stage : fluid::kAllStages) {
        std::printf("%-24s", fluid::stageName(stage));
        for (const GridResult& r : results) {
            auto it = r.stageMs.find(fluid::stageName(stage));
            std::printf(" %12.3f", it == r.stageMs.end() ? 0.0 : it->second);
        }
        std::printf("\n");
    }
    std::printf("%-24s", "whole step (GPU)");
    for (const GridResult& r : results)
        std::printf(" %12.3f", r.stepMs);
    std::printf("\n%-24s", "whole step (wall)");
    for (const GridResult& r : results)
        std::printf(" %12.3f", r.wallMs);
    std::printf("\n");

    if (jsonFile.is_open()) {
        nlohmann::json list = nlohmann::json::array();
        for (const GridResult& r : results)
            list.push_back({{"grid", r.grid},
                            {"workgroup", r.workgroup},
                            {"jacobi", jacobi.value()},
                            {"pressure", fluid::pressureSolverName(*pressure)},
                            {"step_ms", r.stepMs},
                            {"wall_ms", r.wallMs},
                            {"stages", r.stageMs}});
        jsonFile << nlohmann::json{{"device", ctx.info().name},
                                   {"driver", ctx.info().driverInfo},
                                   {"scenario", scenarioName},
                                   {"steps", steps.value()},
                                   {"results", list}}
                        .dump(2)
                 << "\n";
    }
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
