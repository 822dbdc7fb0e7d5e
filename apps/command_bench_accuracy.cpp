// motionfx bench accuracy: what accuracy costs in time. Every configuration of the solver's
// accuracy options (pressure solver and its effort, advection scheme, storage) runs a scenario for
// K steps on the GPU, timed per step with timestamp queries, and its fields are compared with two
// yardsticks on the CPU reference: the same grid with the exact pressure solve in fp32, and a grid
// twice as fine (restricted to this one). Separately, each pressure solver's time to bring a
// smooth divergence at 64^3 down to a relative residual of 1e-3 from a cold start. Writes a table,
// CSV, JSON and an SVG plot (error against milliseconds, log-log, the Pareto front marked).
// The scenarios are fluid/scenarios.h's, and `kick`: the impulses the built-in default scene's
// roundhouse kick splats into its smoke grid, recorded on the GPU (sim/scene_scenario.h) and
// replayed through scenario.emitters() like every other scenario's.
#include "apps/commands.h"
#include "apps/progress.h"
#include "apps/svg_plot.h"

#include "core/gpu/commands.h"
#include "fluid/accuracy.h"
#include "fluid/field_compare.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/scenarios.h"
#include "fluid/smoke_solver.h"
#include "sim/scene_scenario.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

namespace mfx::app {

namespace {

using fluid::AdvectionScheme;
using fluid::FieldState;
using fluid::PressureSolver;
using fluid::SolverOptions;
using fluid::Storage;

// The scenario recorded from the built-in default scene (sim/scene_scenario.h).
constexpr const char* kKick = "kick";

struct Config {
    std::string name;
    std::function<void(SolverOptions&)> apply;
};

std::vector<Config> configs() {
    std::vector<Config> out;
    for (uint32_t n : {10u, 20u, 40u, 80u, 160u})
        out.push_back({"jacobi " + std::to_string(n), [n](SolverOptions& o) {
                           o.pressureSolver = PressureSolver::Jacobi;
                           o.jacobiIterations = n;
                       }});
    for (uint32_t n : {5u, 10u, 20u, 40u})
        out.push_back({"rbgs " + std::to_string(n), [n](SolverOptions& o) {
                           o.pressureSolver = PressureSolver::RedBlackGaussSeidel;
                           o.jacobiIterations = n;
                       }});
    for (uint32_t n : {1u, 2u, 4u})
        out.push_back({"multigrid " + std::to_string(n), [n](SolverOptions& o) {
                           o.pressureSolver = PressureSolver::Multigrid;
                           o.multigrid.cycles = n;
                       }});
    for (float tol : {1e-2f, 1e-3f, 1e-4f}) {
        char name[32];
        std::snprintf(name, sizeof name, "mgpcg %g", double(tol));
        out.push_back({name, [tol](SolverOptions& o) {
                           o.pressureSolver = PressureSolver::MultigridPcg;
                           o.cgTolerance = tol;
                       }});
    }
    for (AdvectionScheme a : {AdvectionScheme::MacCormack, AdvectionScheme::Bfecc})
        out.push_back({std::string(fluid::advectionName(a)) + " (jacobi 20)",
                       [a](SolverOptions& o) { o.advection = a; }});
    out.push_back({"fp16 (jacobi 20)", [](SolverOptions& o) { o.storage = Storage::Float16; }});
    return out;
}

struct Row {
    std::string scenario, config;
    bool gpu = false;             // timed on the GPU (else errors from the CPU reference only)
    std::string note;             // why not on the GPU
    double stepMs = std::nan(""); // median GPU ms per step
    double pressureMs = std::nan("");
    double divergence = 0.0;                        // left after the last projection, relative
    double velocityError = 0.0, pigmentError = 0.0; // vs the same grid, exact pressure, fp32
    double velocityFine = 0.0, pigmentFine = 0.0;   // vs the 2x finer grid
};

struct TimeToTarget {
    std::string option;
    uint32_t effort = 0;   // sweeps, cycles or iterations
    bool reached = false;  // within the cap on the CPU reference
    bool measured = false; // timed on the GPU (else extrapolated or unavailable)
    double ms = std::nan("");
    double gpuResidual = std::nan("");
    std::string note;
};

} // namespace

int runBenchAccuracy(const cli::ParsedArgs& parsed) {
    auto grid = cli::parseUnsigned(parsed.value("grid", "32"), 4, 128, "--grid");
    auto steps = cli::parseUnsigned(parsed.value("steps", "20"), 1, 10000, "--steps");
    auto targetGrid =
        cli::parseUnsigned(parsed.value("target-grid", "64"), 0, 256, "--target-grid");
    if (reportFirstError(grid, steps, targetGrid)) return kExitUsage;
    std::vector<PressureSolver> targetSolvers;
    {
        std::stringstream list(parsed.value("target-solvers", "jacobi,rbgs,multigrid,mgpcg"));
        std::string item;
        while (std::getline(list, item, ',')) {
            const auto solver = fluid::pressureSolverFromName(item);
            if (!solver) {
                printError("--target-solvers: no pressure solver \"" + item +
                           "\"; solvers are jacobi, rbgs, multigrid, mgpcg");
                return kExitUsage;
            }
            targetSolvers.push_back(*solver);
        }
    }
    std::vector<double> budgets;
    {
        std::stringstream list(parsed.value("budgets", "2,5,10,20,50,100,200"));
        std::string item;
        while (std::getline(list, item, ',')) {
            char* end = nullptr;
            const double ms = std::strtod(item.c_str(), &end);
            if (item.empty() || *end != '\0' || !std::isfinite(ms) || ms <= 0.0) {
                printError("--budgets: \"" + item + "\" is not a positive number of milliseconds");
                return kExitUsage;
            }
            budgets.push_back(ms);
        }
        std::sort(budgets.begin(), budgets.end());
    }
    std::vector<std::string> scenarios;
    {
        std::stringstream list(parsed.value("scenarios", "puff,jet,kick"));
        std::string item;
        while (std::getline(list, item, ',')) {
            if (item == kKick) {
                scenarios.push_back(item);
                continue;
            }
            if (auto made = fluid::makeScenario(item, glm::uvec3(4)); !made) {
                printError("--scenarios: " + made.error().message + ", " + kKick);
                return kExitUsage;
            }
            scenarios.push_back(item);
        }
    }
    const std::string csvPath = parsed.value("csv", "out/bench_accuracy.csv");
    const std::string plotPath = parsed.value("plot", "out/bench_accuracy.svg");
    for (const std::string& path : {csvPath, plotPath}) {
        const std::filesystem::path dir = std::filesystem::path(path).parent_path();
        std::error_code error;
        if (!dir.empty()) std::filesystem::create_directories(dir, error);
    }
    std::ofstream csvFile, plotFile, jsonFile;
    if (!openOutputFile(csvPath, csvFile) || !openOutputFile(plotPath, plotFile) ||
        !openOutputFile(parsed.value("json"), jsonFile))
        return kExitFailure;
    const std::unique_ptr<gpu::Context> context = createTimingContext(parsed, "the solver");
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    const uint32_t n = grid.value(), K = steps.value();
    std::printf("accuracy benchmark on %s (%s)\n%u^3 cells, %u steps per run; errors are relative "
                "L2 after the last step\n\n",
                ctx.info().name.c_str(), ctx.info().driverInfo.c_str(), n, K);

    // The kick's impulses, recorded once from the built-in default scene; each grid gets them
    // mapped onto its own domain.
    std::optional<sim::SceneImpulses> kick;
    if (std::find(scenarios.begin(), scenarios.end(), kKick) != scenarios.end()) {
        scene::Scene scene = scene::kickScene();
        // The scenario as it has been measured: the default camera and stage (floor at y = 0),
        // not the framed ones, so the grid's placement, and the impulses in it, stay the same.
        scene.camera.automatic = false;
        Result<anim::Character> character = scene::loadCharacter(scene);
        if (!character) {
            printError(character.error().message);
            return kExitFailure;
        }
        std::printf("kick: recording the impulses of %s ...\n", scene.file.c_str());
        std::fflush(stdout);
        Result<sim::SceneImpulses> recorded =
            sim::recordSceneImpulses(ctx, scene, character.value());
        if (!recorded) {
            printError("kick: " + recorded.error().message);
            return kExitFailure;
        }
        kick = std::move(recorded).value();
        const fluid::GridShape& g = kick->options.grid;
        const uint32_t kept = uint32_t(kick->steps.size());
        const std::string after =
            K > kept ? ", then " + std::to_string(K - kept) + " steps without impulses" : "";
        std::printf("kick: %u steps recorded on the scene's %ux%ux%u grid of %g m cells (%u "
                    "records dropped); the runs take the first %u%s\n",
                    kept, g.cellsX, g.cellsY, g.cellsZ, double(g.cellSize), kick->dropped,
                    std::min(K, kept), after.c_str());
    }
    auto makeScenario = [&](const std::string& name, uint32_t cells) {
        return name == kKick ? sim::makeSceneScenario(*kick, glm::uvec3(cells), kKick)
                             : fluid::makeScenario(name, glm::uvec3(cells));
    };

    nlohmann::json described = nlohmann::json::array();
    for (const std::string& name : scenarios) {
        const std::string description = makeScenario(name, n).value().description;
        std::printf("%-9s %s\n", name.c_str(), description.c_str());
        described.push_back({{"name", name}, {"description", description}});
    }
    std::printf("\n");
    std::fflush(stdout); // before the progress bar on stderr

    const std::vector<Config> all = configs();
    std::vector<Row> rows;
    Progress progress("configurations", uint32_t(all.size() * scenarios.size()));
    uint32_t done = 0;
    for (const std::string& name : scenarios) {
        const fluid::Scenario scenario = makeScenario(name, n).value();
        const fluid::Scenario fineScenario = makeScenario(name, 2 * n).value();
        // The yardsticks: exact pressure, fp32, semi-Lagrangian, on this grid and twice as fine.
        const FieldState exact = fluid::referenceRun(scenario, scenario.options, K, true);
        SolverOptions fineOptions = fineScenario.options;
        fineOptions.dt = scenario.options.dt;
        const FieldState fine = fluid::restrictToCoarse(
            fluid::referenceRun(fineScenario, fineOptions, K, true), scenario.options.grid);
        for (const Config& config : all) {
            Row row{name, config.name};
            SolverOptions o = scenario.options;
            config.apply(o);
            FieldState result;
            auto created = fluid::SmokeSolver::create(ctx, o);
            if (created) {
                fluid::SmokeSolver& solver = *created.value();
                solver.setState(scenario.initial);
                gpu::GpuTimer timer(ctx, solver.passesPerStep());
                std::vector<double> stepMs, pressureMs;
                for (uint32_t s = 0; s < K; ++s) {
                    if (Status ok = solver.setEmitters(scenario.emitters(s)); !ok) {
                        printError(ok.error().message);
                        return kExitFailure;
                    }
                    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
                        timer.reset(cmd);
                        solver.recordStep(cmd, &timer);
                    });
                    double total = 0.0, pressure = 0.0;
                    for (const gpu::PassTime& p : timer.results()) {
                        total += p.milliseconds;
                        if (p.name == "solve_pressure") pressure += p.milliseconds;
                    }
                    // The first steps include the pipelines' compiles.
                    if (s >= std::min(2u, K - 1)) {
                        stepMs.push_back(total);
                        pressureMs.push_back(pressure);
                    }
                }
                result = solver.state();
                row.gpu = true;
                row.stepMs = median(stepMs);
                row.pressureMs = median(pressureMs);
            } else {
                row.note = created.error().message;
                result = fluid::referenceRun(scenario, o, K, false);
            }
            row.divergence = fluid::divergenceLeft(o, result);
            const fluid::StateDifference toExact = fluid::difference(result, exact);
            const fluid::StateDifference toFine = fluid::difference(result, fine);
            row.velocityError = toExact.velocity.relL2;
            row.pigmentError = toExact.pigment.relL2;
            row.velocityFine = toFine.velocity.relL2;
            row.pigmentFine = toFine.pigment.relL2;
            rows.push_back(row);
            progress.update(++done);
        }
    }
    progress.finish();

    std::printf("%-9s %-28s %9s %9s %10s %10s %10s %10s %10s\n", "scenario", "configuration",
                "step ms", "p ms", "div left", "vel err", "pig err", "vel fine", "pig fine");
    for (const Row& r : rows) {
        char ms[32] = "   (cpu)", pms[32] = "";
        if (r.gpu) {
            std::snprintf(ms, sizeof ms, "%9.2f", r.stepMs);
            std::snprintf(pms, sizeof pms, "%9.2f", r.pressureMs);
        }
        std::printf("%-9s %-28s %9s %9s %10.2e %10.2e %10.2e %10.2e %10.2e\n", r.scenario.c_str(),
                    r.config.c_str(), ms, pms, r.divergence, r.velocityError, r.pigmentError,
                    r.velocityFine, r.pigmentFine);
    }
    // The best configuration within each budget of GPU ms per step: the least velocity error
    // against the grid twice as fine (the closest to the flow itself: it sees the advection scheme
    // and the storage as well as the pressure solve; the same-grid error sees the pressure solve
    // alone, and is printed beside it).
    struct BudgetPick {
        std::string scenario;
        double budget = 0.0;
        const Row* best = nullptr;
        double fastest = std::nan("");
    };
    std::vector<BudgetPick> picks;
    std::printf("\nbest per budget (least velocity error against the 2x finer grid):\n");
    for (const std::string& name : scenarios)
        for (double budget : budgets) {
            BudgetPick pick{name, budget};
            for (const Row& r : rows) {
                if (r.scenario != name || !r.gpu) continue;
                if (!(pick.fastest <= r.stepMs)) pick.fastest = r.stepMs;
                // Equal errors (e.g. two MGPCG tolerances met by the same iteration): the faster.
                if (r.stepMs <= budget &&
                    (!pick.best || r.velocityFine < pick.best->velocityFine ||
                     (r.velocityFine == pick.best->velocityFine && r.stepMs < pick.best->stepMs)))
                    pick.best = &r;
            }
            if (pick.best)
                std::printf("%-9s <= %6.1f ms  %-28s %7.2f ms  vel fine %.3e  vel exact %.3e\n",
                            name.c_str(), budget, pick.best->config.c_str(), pick.best->stepMs,
                            pick.best->velocityFine, pick.best->velocityError);
            else
                std::printf("%-9s <= %6.1f ms  none (the fastest configuration takes %.2f ms)\n",
                            name.c_str(), budget, pick.fastest);
            picks.push_back(pick);
        }
    for (const Row& r : rows)
        if (!r.gpu) {
            std::printf("(cpu): the GPU solver refused the configuration on this device (%s); "
                        "errors from the CPU reference, no time.\n",
                        r.note.c_str());
            break;
        }

    // Time to a relative residual of 1e-3 from a cold start, smooth divergence.
    std::vector<TimeToTarget> targets;
    const uint32_t tn = targetGrid.value();
    if (tn > 0) {
        std::printf("\ntime to a relative residual of 1e-3 at %u^3 (cold start, smooth "
                    "divergence):\n",
                    tn);
        SolverOptions base;
        base.grid = {tn, tn, tn, 1.0f / float(tn)};
        const FieldState input = fluid::smoothDivergentState(base);
        struct Candidate {
            std::string name;
            PressureSolver solver;
            uint32_t cap;
        };
        for (const Candidate& c : {Candidate{"jacobi", PressureSolver::Jacobi, 4000},
                                   Candidate{"rbgs", PressureSolver::RedBlackGaussSeidel, 2000},
                                   Candidate{"multigrid", PressureSolver::Multigrid, 20},
                                   Candidate{"mgpcg", PressureSolver::MultigridPcg, 20}}) {
            if (std::find(targetSolvers.begin(), targetSolvers.end(), c.solver) ==
                targetSolvers.end())
                continue;
            TimeToTarget t{c.name};
            SolverOptions o = base;
            o.pressureSolver = c.solver;
            // The effort needed, from the reference's residual history (the same arithmetic).
            if (c.solver == PressureSolver::Multigrid) o.multigrid.cycles = c.cap;
            if (c.solver == PressureSolver::MultigridPcg) {
                o.cgTolerance = 1e-3f;
                o.cgMaxIterations = c.cap;
            } else {
                o.jacobiIterations = c.cap;
            }
            fluid::ReferenceSolver ref(o);
            ref.setState(input);
            ref.setRecordResidualHistory(true);
            ref.solvePressure();
            const std::vector<double>& history = ref.residualHistory();
            size_t hit = history.size();
            for (size_t i = 0; i < history.size(); ++i)
                if (history[i] <= 1e-3) {
                    hit = i;
                    break;
                }
            double rate = 1.0;
            if (hit < history.size()) {
                t.reached = true;
                t.effort = uint32_t(hit);
            } else if (history.size() > 100) {
                // Extrapolated from the rate over the last quarter of the capped run.
                const size_t a = history.size() * 3 / 4, b = history.size() - 1;
                rate = std::pow(history[b] / history[a], 1.0 / double(b - a));
                t.effort = uint32_t(double(b) + std::log(1e-3 / history[b]) / std::log(rate));
                t.note = "extrapolated from the residual rate of the last " +
                         std::to_string(b - a) + " of " + std::to_string(b) + " sweeps";
            }
            // The GPU's time for that effort (a capped effort timed as run, then scaled).
            SolverOptions timed = o;
            const uint32_t runEffort = t.reached ? t.effort : c.cap;
            if (c.solver == PressureSolver::Multigrid) timed.multigrid.cycles = runEffort;
            if (c.solver == PressureSolver::Jacobi ||
                c.solver == PressureSolver::RedBlackGaussSeidel)
                timed.jacobiIterations = runEffort;
            auto created = fluid::SmokeSolver::create(ctx, timed);
            if (!created) {
                t.note = created.error().message;
            } else if (runEffort > 0) {
                // The solve from a cold start does the same work each time (the divergence
                // stays), so a submit of kSolves solves back to back times it; the first submit
                // compiles and, on a GPU, takes the clocks out of idle, which a lone solve of a
                // millisecond between idle waits does not (an H200 timed 3 V-cycles at 128³
                // about four times slower so).
                constexpr int kSolves = 8;
                fluid::SmokeSolver& solver = *created.value();
                gpu::GpuTimer timer(ctx, 4 * kSolves);
                std::vector<double> ms;
                solver.setState(input);
                for (int repeat = 0; repeat < 4; ++repeat) {
                    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
                        timer.reset(cmd);
                        for (int k = 0; k < kSolves; ++k)
                            solver.recordStage(cmd, fluid::Stage::SolvePressure, &timer);
                    });
                    double total = 0.0;
                    for (const gpu::PassTime& p : timer.results())
                        total += p.milliseconds;
                    if (repeat > 0) ms.push_back(total / kSolves);
                }
                t.measured = true;
                t.ms = median(ms) * (t.reached ? 1.0 : double(t.effort) / double(runEffort));
                fluid::ReferenceSolver check(timed);
                check.setState(solver.state());
                t.gpuResidual = check.pressureResidual();
            }
            char ms[32] = "-", residual[64] = "";
            if (t.measured) std::snprintf(ms, sizeof ms, "%.2f", t.ms);
            if (t.measured && t.reached)
                std::snprintf(residual, sizeof residual, " (GPU residual %.2e)", t.gpuResidual);
            std::printf("  %-10s %6u %-10s %10s ms  %s%s\n", t.option.c_str(), t.effort,
                        c.solver == PressureSolver::Multigrid      ? "V-cycles"
                        : c.solver == PressureSolver::MultigridPcg ? "iterations"
                                                                   : "sweeps",
                        ms, t.note.c_str(), residual);
            targets.push_back(t);
        }
    }

    // CSV, plot and JSON.
    csvFile << "scenario,configuration,gpu,step_ms,pressure_ms,divergence_left,velocity_error,"
               "pigment_error,velocity_error_fine,pigment_error_fine\n";
    for (const Row& r : rows)
        csvFile << r.scenario << ",\"" << r.config << "\"," << (r.gpu ? 1 : 0) << ","
                << (r.gpu ? std::to_string(r.stepMs) : "") << ","
                << (r.gpu ? std::to_string(r.pressureMs) : "") << "," << r.divergence << ","
                << r.velocityError << "," << r.pigmentError << "," << r.velocityFine << ","
                << r.pigmentFine << "\n";
    std::vector<PlotPanel> panels;
    const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd"};
    for (size_t si = 0; si < scenarios.size(); ++si) {
        PlotPanel panel;
        panel.title = scenarios[si] + ": velocity error vs exact pressure";
        panel.xLabel = "GPU ms per step";
        panel.yLabel = "relative L2 error";
        panel.logX = panel.logY = true;
        PlotSeries points{"configurations", colours[si % 4], {}, {}};
        std::vector<std::pair<double, double>> timed;
        for (const Row& r : rows)
            if (r.scenario == scenarios[si] && r.gpu && r.velocityError > 0.0)
                timed.push_back({r.stepMs, r.velocityError});
        std::sort(timed.begin(), timed.end());
        PlotSeries front{"Pareto front", "#000000", {}, {}};
        double best = std::numeric_limits<double>::infinity();
        for (const auto& [ms, err] : timed) {
            points.x.push_back(ms);
            points.y.push_back(err);
            if (err < best) {
                best = err;
                front.x.push_back(ms);
                front.y.push_back(err);
            }
        }
        panel.series = {points, front};
        panels.push_back(panel);
    }
    plotFile << svgPlot("accuracy against time on " + ctx.info().name, panels);
    std::printf("\ntable in %s, plot in %s\n", csvPath.c_str(), plotPath.c_str());

    if (jsonFile.is_open()) {
        nlohmann::json results = nlohmann::json::array();
        for (const Row& r : rows)
            results.push_back(
                {{"scenario", r.scenario},
                 {"configuration", r.config},
                 {"gpu", r.gpu},
                 {"note", r.note},
                 {"step_ms", r.gpu ? nlohmann::json(r.stepMs) : nlohmann::json()},
                 {"pressure_ms", r.gpu ? nlohmann::json(r.pressureMs) : nlohmann::json()},
                 {"divergence_left", r.divergence},
                 {"velocity_error", r.velocityError},
                 {"pigment_error", r.pigmentError},
                 {"velocity_error_fine", r.velocityFine},
                 {"pigment_error_fine", r.pigmentFine}});
        nlohmann::json doc{{"device", ctx.info().name},
                           {"grid", {n, n, n}},
                           {"steps", K},
                           {"scenarios", described},
                           {"results", results}};
        nlohmann::json perBudget = nlohmann::json::array();
        for (const BudgetPick& p : picks)
            perBudget.push_back(
                {{"scenario", p.scenario},
                 {"budget_ms", p.budget},
                 {"best", p.best ? nlohmann::json(p.best->config) : nlohmann::json()},
                 {"step_ms", p.best ? nlohmann::json(p.best->stepMs) : nlohmann::json()},
                 {"velocity_error_fine",
                  p.best ? nlohmann::json(p.best->velocityFine) : nlohmann::json()},
                 {"velocity_error",
                  p.best ? nlohmann::json(p.best->velocityError) : nlohmann::json()}});
        doc["budgets"] = perBudget;
        if (kick)
            doc["kick"] = {
                {"scene", kick->scene},
                {"scene_grid",
                 {kick->options.grid.cellsX, kick->options.grid.cellsY, kick->options.grid.cellsZ}},
                {"scene_cell_size", kick->options.grid.cellSize},
                {"dt", kick->options.dt},
                {"first_scene_step", kick->firstStep},
                {"recorded_steps", kick->steps.size()},
                {"dropped", kick->dropped}};
        if (!targets.empty()) {
            nlohmann::json each = nlohmann::json::object();
            const TimeToTarget* jacobi = nullptr;
            const TimeToTarget* best = nullptr;
            for (const TimeToTarget& t : targets) {
                each[t.option] = {{"effort", t.effort},
                                  {"ms", t.measured ? nlohmann::json(t.ms) : nlohmann::json()},
                                  {"reached_within_cap", t.reached},
                                  {"note", t.note}};
                if (t.option == "jacobi") jacobi = &t;
                if (t.measured && (!best || t.ms < best->ms)) best = &t;
            }
            doc["time_to_1e-3"] = {{"grid", {tn, tn, tn}},
                                   {"jacobi_ms", jacobi && jacobi->measured
                                                     ? nlohmann::json(jacobi->ms)
                                                     : nlohmann::json()},
                                   {"jacobi_extrapolated", jacobi && !jacobi->reached},
                                   {"best_ms", best ? nlohmann::json(best->ms) : nlohmann::json()},
                                   {"best_option", best ? best->option : ""},
                                   {"options", each}};
        }
        jsonFile << doc.dump(2) << "\n";
    }
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
