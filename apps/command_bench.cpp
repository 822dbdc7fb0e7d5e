// motionfx bench: benchmark programs that print tables (never pass/fail on time).
//   motionfx bench solver       GPU milliseconds per solver stage and per step, by grid size, and
//                               the roofline: the bytes each stage must move (its model in
//                               fluid/stage_table.cpp), the rate it reaches, and that rate's share
//                               of the device's copy bandwidth measured in the same run.
//   motionfx bench trajectory   split trajectory against the unsplit baseline, by lifetime
//                               (command_bench_trajectory.cpp).
#include "apps/bench_report.h"
#include "apps/commands.h"
#include "apps/svg_plot.h"

#include "core/anim/fighter.h"
#include "core/anim/sampling.h"
#include "core/gpu/bandwidth.h"
#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "core/gpu/timer.h"
#include "fluid/body_solids.h"
#include "fluid/gpu_multigrid.h"
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

// --solids: none, the fighter's body, or both side by side.
enum class BenchSolids { None, Body, Both };

struct GridResult {
    std::array<uint32_t, 3> grid;
    std::array<uint32_t, 3> workgroup;
    double stepMs = 0.0;                   // median GPU time of a whole step (sum of its stages)
    double wallMs = 0.0;                   // median CPU wall time of record + submit + wait
    std::map<std::string, double> stageMs; // median per stage
    std::map<std::string, fluid::StageBytes> stageBytes; // the model, per stage (summed over runs)
    fluid::StageBytes stepBytes;
    uint32_t dispatches = 0; // compute dispatches a step (each followed, mostly, by a barrier)
    bool withBody = false;   // the fighter's body as solids
};

// Cells of the box the emitters cover (their spheres' bounds, clipped to the grid): what the
// splat reads and writes.
uint64_t splatCells(const fluid::SolverOptions& o, std::span<const shared::FluidEmitter> emitters) {
    if (emitters.empty()) return 0;
    const glm::vec3 n(float(o.grid.cellsX), float(o.grid.cellsY), float(o.grid.cellsZ));
    glm::vec3 low(1e30f), high(-1e30f);
    for (const shared::FluidEmitter& e : emitters) {
        const glm::vec3 p = glm::vec3(e.positionRadius) / o.grid.cellSize;
        const float r = e.positionRadius.w / o.grid.cellSize;
        low = glm::min(low, glm::floor(p - r));
        high = glm::max(high, glm::ceil(p + r));
    }
    // The box's cells inside the grid (none when it lies outside).
    const glm::vec3 size = glm::max(glm::min(high, n) - glm::max(low, glm::vec3(0.0f)), 0.0f);
    return uint64_t(size.x) * uint64_t(size.y) * uint64_t(size.z);
}

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

// The solver options bench solver sets on every grid's scenario.
struct SolverChoice {
    uint32_t jacobi = 20;
    fluid::PressureSolver pressure = fluid::PressureSolver::Jacobi;
    fluid::StorePath store = fluid::StorePath::Auto;
    uint32_t coarseGroup = 0;
    uint32_t brick = 0;
    uint32_t coarseCells = 0;
    fluid::ByDevice residualInRestriction = fluid::ByDevice::Auto;
    fluid::ByDevice firstSweepInDivergence = fluid::ByDevice::Auto;
    BenchSolids solids = BenchSolids::None; // --solids
    fluid::ByDevice solidLists = fluid::ByDevice::Auto;
    float turbulence = 0.0f; // --turbulence: m/s^2, 0 the scenario's (off)
};

// The solids of --solids body: the built-in fighter's capsules (core/anim/body_capsules.h) in the
// roundhouse kick at 0.4 s, the leg out, moving as over the next `dt`; scaled by half (0.9 m tall)
// and stood in the middle of the grid's floor, in a box `box` world units across.
std::vector<shared::FluidSolid> benchBodySolids(glm::vec3 box, float dt) {
    const anim::Character fighter = anim::makeFighter();
    const anim::Clip* kick = fighter.findClip("roundhouse_kick");
    const std::vector<anim::BodyCapsule> capsules = anim::fitBodyCapsules(fighter);
    const float t = 0.4f, scale = 0.5f;
    std::vector<shared::FluidSolid> solids =
        fluid::bodySolids(capsules, anim::samplePose(fighter, kick, t),
                          anim::samplePose(fighter, kick, t + dt), dt, glm::vec3(0.0f));
    const glm::vec3 offset(0.5f * box.x, 0.02f * box.y, 0.5f * box.z);
    for (shared::FluidSolid& s : solids) {
        s.endA = glm::vec4(glm::vec3(s.endA) * scale + offset, s.endA.w * scale);
        s.endB = glm::vec4(glm::vec3(s.endB) * scale + offset, 0.0f);
        s.velocityA *= scale;
        s.velocityB *= scale;
    }
    return solids;
}

// One solver of a benchmarked grid and the times of its steps.
struct GridRun {
    fluid::Scenario scenario;
    std::unique_ptr<fluid::SmokeSolver> solver;
    std::unique_ptr<gpu::GpuTimer> timer;
    std::vector<shared::FluidSolid> solids;
    std::vector<double> stepTimes, wallTimes;
    std::map<std::string, std::vector<double>> stageTimes;
};

Result<std::unique_ptr<GridRun>>
makeGridRun(const gpu::Context& ctx, const std::string& scenarioName, std::array<uint32_t, 3> cells,
            std::array<uint32_t, 3> workgroup, const SolverChoice& choice, bool body) {
    auto run = std::make_unique<GridRun>();
    run->scenario =
        fluid::makeScenario(scenarioName, glm::uvec3(cells[0], cells[1], cells[2])).value();
    fluid::SolverOptions& o = run->scenario.options;
    o.jacobiIterations = choice.jacobi;
    o.pressureSolver = choice.pressure;
    o.workgroup = workgroup;
    o.storePath = choice.store;
    o.multigrid.coarseGroup = choice.coarseGroup;
    o.multigrid.brick = choice.brick;
    o.multigrid.coarseCells = choice.coarseCells;
    o.multigrid.residualInRestriction = choice.residualInRestriction;
    o.firstSweepInDivergence = choice.firstSweepInDivergence;
    o.solidLists = choice.solidLists;
    if (choice.turbulence > 0.0f) o.turbulence = choice.turbulence;
    auto solverResult = fluid::SmokeSolver::create(ctx, o);
    if (!solverResult) return solverResult.error();
    run->solver = std::move(solverResult).value();
    run->solver->setState(run->scenario.initial);
    if (body) {
        const fluid::GridShape& g = o.grid;
        run->solids =
            benchBodySolids(glm::vec3(g.cellsX, g.cellsY, g.cellsZ) * g.cellSize, o.substepDt());
        if (Status ok = run->solver->setSolids(run->solids); !ok) return ok.error();
    }
    run->timer = std::make_unique<gpu::GpuTimer>(ctx, run->solver->passesPerStep());
    return run;
}

// One step of `run`, its times kept unless `warmup`.
Status stepGridRun(const gpu::Context& ctx, GridRun& run, bool warmup) {
    fluid::SmokeSolver& solver = *run.solver;
    // Emitters stay on (the scenario's first step) so every stage has work each step.
    if (Status ok = solver.setEmitters(run.scenario.emitters(0)); !ok) return ok;
    const auto start = std::chrono::steady_clock::now();
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        run.timer->reset(cmd);
        solver.recordStep(cmd, run.timer.get());
    });
    const double wall =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::fputc('.', stderr);
    if (warmup) return Ok{};
    std::map<std::string, double> perStage;
    double total = 0.0;
    for (const gpu::PassTime& pass : run.timer->results()) {
        perStage[pass.name] += pass.milliseconds;
        total += pass.milliseconds;
    }
    for (const auto& [name, ms] : perStage)
        run.stageTimes[name].push_back(ms);
    run.stepTimes.push_back(total);
    run.wallTimes.push_back(wall);
    return Ok{};
}

GridResult gridResult(const GridRun& run, std::array<uint32_t, 3> cells,
                      std::array<uint32_t, 3> workgroup) {
    const fluid::Scenario& scenario = run.scenario;
    GridResult r{cells, workgroup, median(run.stepTimes), median(run.wallTimes), {}, {}, {}, 0};
    for (const auto& [name, times] : run.stageTimes)
        r.stageMs[name] = median(times);
    const fluid::StageWork work{splatCells(scenario.options, scenario.emitters(0)),
                                run.solver->lastPressureIterations(), uint32_t(run.solids.size())};
    for (fluid::Stage stage : fluid::stepOrder()) {
        const fluid::StageBytes b = fluid::stageEntry(stage).bytes(scenario.options, work);
        fluid::StageBytes& sum = r.stageBytes[fluid::stageName(stage)];
        sum.read += b.read * scenario.options.substeps;
        sum.written += b.written * scenario.options.substeps;
    }
    r.stepBytes = fluid::stepBytes(scenario.options, work);
    for (const auto& [stage, count] : run.solver->lastStepDispatches())
        r.dispatches += count;
    r.stepBytes.read *= scenario.options.substeps;
    r.stepBytes.written *= scenario.options.substeps;
    r.withBody = !run.solids.empty();
    return r;
}

// Times one grid with one workgroup shape: the median of `steps` steps after 3 warm-up steps.
// With --solids both, two solvers, without and with the body, step by turns (so that a drift of
// the machine's speed reaches both alike): two results, the second with the body, and the median
// of the steps' ratios in `ratio`.
Result<std::vector<GridResult>> benchGrid(const gpu::Context& ctx, const std::string& scenarioName,
                                          std::array<uint32_t, 3> cells,
                                          std::array<uint32_t, 3> workgroup,
                                          const SolverChoice& choice, uint32_t steps,
                                          double* ratio) {
    std::vector<std::unique_ptr<GridRun>> runs;
    for (bool body : {false, true}) {
        if (body ? choice.solids == BenchSolids::None : choice.solids == BenchSolids::Body)
            continue;
        auto run = makeGridRun(ctx, scenarioName, cells, workgroup, choice, body);
        if (!run) return run.error();
        runs.push_back(std::move(run).value());
    }
    std::fprintf(stderr, "  %ux%ux%u, workgroup %s ", cells[0], cells[1], cells[2],
                 shapeLabel(workgroup).c_str());
    const uint32_t warmup = 3;
    for (uint32_t step = 0; step < warmup + steps; ++step)
        for (auto& run : runs)
            if (Status ok = stepGridRun(ctx, *run, step < warmup); !ok) return ok.error();
    std::fputc('\n', stderr);
    std::vector<GridResult> results;
    for (const auto& run : runs)
        results.push_back(gridResult(*run, cells, workgroup));
    if (runs.size() == 2 && ratio != nullptr) {
        std::vector<double> ratios;
        for (size_t i = 0; i < runs[0]->stepTimes.size(); ++i)
            ratios.push_back(runs[1]->stepTimes[i] / runs[0]->stepTimes[i]);
        *ratio = median(ratios);
    }
    return results;
}

} // namespace

int runBenchSolver(const cli::ParsedArgs& parsed) {
    const std::string domain = parsed.value("domain", "dense");
    if (domain == "sparse") {
        for (const char* denseOnly :
             {"store", "copy-mib", "markdown", "workgroups", "coarse-group", "brick",
              "coarse-cells", "residual-in-restriction", "first-sweep-in-divergence", "solids",
              "solid-lists", "turbulence"})
            if (parsed.has(denseOnly)) {
                printError(std::string("--") + denseOnly + " is an option of the dense domain");
                return kExitUsage;
            }
        return runBenchSparse(parsed);
    }
    if (domain != "dense") {
        printError("--domain must be dense or sparse, not \"" + domain + "\"");
        return kExitUsage;
    }
    for (const char* sparseOnly : {"virtual", "bricks"})
        if (parsed.has(sparseOnly)) {
            printError(std::string("--") + sparseOnly + " is an option of --domain sparse");
            return kExitUsage;
        }
    auto grids = parseGridList(parsed.value("grids", "32,64,96,128"));
    auto jacobi = cli::parseUnsigned(parsed.value("jacobi", "20"), 0, 100000, "--jacobi");
    auto steps = cli::parseUnsigned(parsed.value("steps", "10"), 1, 10000, "--steps");
    auto workgroups = parseWorkgroupList(
        parsed.value("workgroups", shapeLabel(fluid::SolverOptions{}.workgroup)));
    auto copyMib = cli::parseUnsigned(parsed.value("copy-mib", "256"), 1, 4096, "--copy-mib");
    auto coarseGroup =
        cli::parseUnsigned(parsed.value("coarse-group", "0"), 0, 1024, "--coarse-group");
    auto brick = cli::parseUnsigned(parsed.value("brick", "0"), 0, 4, "--brick");
    auto coarseCells =
        cli::parseUnsigned(parsed.value("coarse-cells", "0"), 0, 4096, "--coarse-cells");
    auto turbulence =
        cli::parseNumber(parsed.value("turbulence", "0"), 0.0, 1000.0, "--turbulence");
    if (reportFirstError(grids, jacobi, steps, workgroups, copyMib, coarseGroup, brick, coarseCells,
                         turbulence))
        return kExitUsage;
    if (brick.value() == 3) {
        printError("--brick must be 0 (by device), 1, 2 or 4, not 3");
        return kExitUsage;
    }
    std::optional<fluid::ByDevice> fused, firstSweep, solidLists;
    for (auto [option, choice] : {std::pair{"residual-in-restriction", &fused},
                                  std::pair{"first-sweep-in-divergence", &firstSweep},
                                  std::pair{"solid-lists", &solidLists}}) {
        *choice = fluid::byDeviceFromName(parsed.value(option, "auto"));
        if (!*choice) {
            printError(std::string("--") + option + " must be auto, on or off, not \"" +
                       parsed.value(option) + "\"");
            return kExitUsage;
        }
    }
    const auto pressure = fluid::pressureSolverFromName(parsed.value("pressure", "jacobi"));
    if (!pressure) {
        printError("--pressure: no pressure solver \"" + parsed.value("pressure") +
                   "\"; solvers are jacobi, rbgs, multigrid, mgpcg");
        return kExitUsage;
    }
    const auto store = fluid::storePathFromName(parsed.value("store", "auto"));
    if (!store) {
        printError("--store: no store path \"" + parsed.value("store") +
                   "\"; paths are auto, buffer, direct");
        return kExitUsage;
    }
    const std::string solidsName = parsed.value("solids", "none");
    if (solidsName != "none" && solidsName != "body" && solidsName != "both") {
        printError("--solids must be none, body or both, not \"" + solidsName + "\"");
        return kExitUsage;
    }
    const BenchSolids benchSolids = solidsName == "body"   ? BenchSolids::Body
                                    : solidsName == "both" ? BenchSolids::Both
                                                           : BenchSolids::None;
    const bool bodySolids = benchSolids != BenchSolids::None;
    const std::string scenarioName = parsed.value("scenario", "puff");
    if (!fluid::makeScenario(scenarioName, {2, 2, 2})) {
        printError(fluid::makeScenario(scenarioName, {2, 2, 2}).error().message);
        return kExitUsage;
    }
    const std::string jsonPath = parsed.value("json");
    std::ofstream jsonFile, plotFile;
    if (!openOutputFile(jsonPath, jsonFile)) return kExitFailure;
    if (!openOutputFile(parsed.value("plot"), plotFile)) return kExitFailure;
    if (parsed.has("markdown"))
        if (Status ok = checkMarkdownFile(parsed.value("markdown")); !ok) {
            printError(ok.error().message);
            return kExitFailure;
        }

    const std::unique_ptr<gpu::Context> context = createTimingContext(parsed, "the solver");
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    const bool direct = fluid::storesDirect(*store, ctx);
    std::printf("smoke solver benchmark on %s (%s)\nscenario %s, pressure solver %s, %u Jacobi "
                "sweeps, whole fields stored %s, median of %u steps after 3 warm-up steps; GPU "
                "milliseconds from timestamp queries\n\n",
                ctx.info().name.c_str(), ctx.info().driverInfo.c_str(), scenarioName.c_str(),
                fluid::pressureSolverName(*pressure), jacobi.value(),
                direct ? "straight into the images" : "into buffers copied into the images",
                steps.value());
    const uint32_t bricks = fluid::multigridBrick(brick.value(), ctx);
    const uint32_t fusedCells = fluid::coarseCycleCells(coarseCells.value());
    const uint32_t coarse =
        fluid::coarseCycleGroup(coarseGroup.value(), bricks, coarseCells.value(), ctx);
    const bool hierarchy = *pressure == fluid::PressureSolver::Multigrid ||
                           *pressure == fluid::PressureSolver::MultigridPcg;
    fluid::SolverOptions resolved;
    resolved.pressureSolver = *pressure;
    resolved.multigrid.residualInRestriction = *fused;
    const bool residualFused = fluid::residualInRestriction(resolved, ctx);
    resolved.jacobiIterations = jacobi.value();
    resolved.firstSweepInDivergence = *firstSweep;
    const bool firstSweepFused = resolved.firstSweepFused();
    const bool splitSolids = fluid::splitsSolids(*solidLists, ctx);
    if (bodySolids)
        std::printf("solids: the fighter's body, %zu capsules mid-kick (--solids %s); the "
                    "stages %s\n\n",
                    benchBodySolids(glm::vec3(1.0f), 1.0f / 60.0f).size(), solidsName.c_str(),
                    splitSolids ? "split into the blocks away from and near them (--solid-lists)"
                                : "dispatched whole (--solid-lists)");
    if (*pressure == fluid::PressureSolver::Jacobi)
        std::printf("the first sweep %s\n\n", firstSweepFused ? "computed by the divergence pass"
                                                              : "computed by the pressure pass");
    if (hierarchy)
        std::printf("bricks of 4 cells by %u rows by %u layers an invocation; the coarse levels "
                    "(%u cells and below) cycled by one workgroup of %u invocations; the residual "
                    "%s\n\n",
                    bricks, bricks, fusedCells, coarse,
                    residualFused ? "computed by the restriction"
                                  : "written by a pass before the restriction");

    std::vector<GridResult> results;
    std::vector<double> bodyRatios; // --solids both: per grid, the median step ratio
    for (const auto& cells : grids.value())
        for (const auto& workgroup : workgroups.value()) {
            double ratio = 0.0;
            auto r = benchGrid(ctx, scenarioName, cells, workgroup,
                               {jacobi.value(), *pressure, *store, coarseGroup.value(),
                                brick.value(), coarseCells.value(), *fused, *firstSweep,
                                benchSolids, *solidLists, float(turbulence.value())},
                               steps.value(), &ratio);
            if (!r) {
                printError(r.error().message);
                return kExitFailure;
            }
            for (GridResult& one : r.value())
                results.push_back(std::move(one));
            if (benchSolids == BenchSolids::Both) bodyRatios.push_back(ratio);
        }

    // The yardstick, after the grids (a GPU has left its idle clock by then): a copy as large as
    // asked, within one storage buffer binding.
    const uint64_t copyBytes =
        std::min<uint64_t>(uint64_t(copyMib.value()) << 20, ctx.limits().maxStorageBufferRange);
    std::fprintf(stderr, "  copy bandwidth, %.0f MiB ", double(copyBytes) / (1 << 20));
    const gpu::CopyBandwidth copy = gpu::measureCopyBandwidth(ctx, copyBytes);
    std::fprintf(stderr, "\n");

    // Table 1: one row per stage (in the table's order), one column per grid (and workgroup).
    const bool shapes = workgroups.value().size() > 1;
    auto gridLabel = [&](const GridResult& r) {
        return shapeLabel(r.grid) + (shapes ? " " + shapeLabel(r.workgroup) : "") +
               (benchSolids == BenchSolids::Both && r.withBody ? " body" : "");
    };
    MarkdownTable times, rates;
    times.header = rates.header = {"stage"};
    for (const GridResult& r : results) {
        times.header.push_back(gridLabel(r) + " ms");
        rates.header.push_back(gridLabel(r) + " GB/s (copy %)");
    }
    auto rate = [&](double bytes, double ms) { return ms > 0.0 ? bytes / (ms * 1e6) : 0.0; };
    auto rateCell = [&](double bytes, double ms) {
        const double gbps = rate(bytes, ms);
        if (bytes == 0.0) return std::string("-");
        return fixed(gbps, 1) + " (" +
               (copy.gigabytesPerSecond > 0.0
                    ? fixed(100.0 * gbps / copy.gigabytesPerSecond, 0) + "%"
                    : std::string("?")) +
               ")";
    };
    for (fluid::Stage stage : fluid::stepOrder()) {
        const std::string name = fluid::stageName(stage);
        std::vector<std::string> t{name}, g{name};
        for (const GridResult& r : results) {
            auto it = r.stageMs.find(name);
            const double ms = it == r.stageMs.end() ? 0.0 : it->second;
            auto bytes = r.stageBytes.find(name);
            t.push_back(fixed(ms, 3));
            g.push_back(rateCell(bytes == r.stageBytes.end() ? 0.0 : bytes->second.total(), ms));
        }
        times.rows.push_back(t);
        rates.rows.push_back(g);
    }
    std::vector<std::string> stepRow{"whole step (GPU)"}, wallRow{"whole step (wall)"},
        stepRate{"whole step"}, dispatchRow{"dispatches a step (count)"};
    for (const GridResult& r : results) {
        stepRow.push_back(fixed(r.stepMs, 3));
        wallRow.push_back(fixed(r.wallMs, 3));
        stepRate.push_back(rateCell(r.stepBytes.total(), r.stepMs));
        dispatchRow.push_back(std::to_string(r.dispatches));
    }
    times.rows.push_back(stepRow);
    times.rows.push_back(wallRow);
    times.rows.push_back(dispatchRow);
    rates.rows.push_back(stepRate);

    auto printTable = [](const MarkdownTable& table) {
        for (size_t i = 0; i < table.header.size(); ++i)
            std::printf(i == 0 ? "%-24s" : " %22s", table.header[i].c_str());
        std::printf("\n");
        for (const auto& row : table.rows) {
            for (size_t i = 0; i < row.size(); ++i)
                std::printf(i == 0 ? "%-24s" : " %22s", row[i].c_str());
            std::printf("\n");
        }
    };
    printTable(times);
    // --solids both: the two solvers stepped by turns, so the ratio of each pair of steps
    // compares them at one moment of the machine's speed.
    std::string ratioLine;
    for (size_t i = 0; i < bodyRatios.size(); ++i)
        ratioLine += (i == 0 ? "" : ", ") + shapeLabel(results[2 * i].grid) + " " +
                     fixed(bodyRatios[i], 3) + "x";
    if (!bodyRatios.empty())
        std::printf("\nthe step with the body over the step without (median of the steps' ratios, "
                    "the two solvers stepped by turns): %s\n",
                    ratioLine.c_str());
    std::printf("\nroofline: copy bandwidth %.1f GB/s (%.0f MiB read and written, median %.3f ms "
                "of 10%s); each stage's rate is the bytes its model must move over its median "
                "time\n\n",
                copy.gigabytesPerSecond, double(copy.bytes) / (1 << 20), copy.medianMs,
                copy.fromWallClock ? ", wall clock: the timestamps did not bracket it" : "");
    printTable(rates);
    std::printf("\nthe bytes models (fluid/stage_table.cpp):\n");
    for (fluid::Stage stage : fluid::stepOrder())
        std::printf("  %-22s %s\n", fluid::stageName(stage), fluid::stageEntry(stage).bytesModel);

    if (parsed.has("markdown")) {
        std::string body =
            times.text() + "\nCopy bandwidth " + fixed(copy.gigabytesPerSecond, 1) + " GB/s" +
            (copy.fromWallClock ? " (wall clock: the timestamps did not bracket it)" : "") +
            "; each stage's rate is the bytes its model "
            "(fluid/stage_table.cpp) must move over its median time:\n\n" +
            rates.text();
        const std::string title =
            std::string("Solver stages, ") + fluid::pressureSolverName(*pressure) + " pressure, " +
            (hierarchy ? "bricks of " + std::to_string(bricks) + " rows, coarse group " +
                             std::to_string(coarse) +
                             (fusedCells != 4096 ? " from " + std::to_string(fusedCells) + " cells"
                                                 : std::string()) +
                             ", " + (residualFused ? "residual in the restriction, " : "")
                       : std::string()) +
            (*pressure == fluid::PressureSolver::Jacobi && !firstSweepFused
                 ? "first sweep in the solve, "
                 : "") +
            (direct ? "direct" : "buffer") + " store (" + scenarioName +
            (bodySolids ? std::string(benchSolids == BenchSolids::Both
                                          ? ", without and with the fighter's body as solids"
                                          : ", the fighter's body as solids") +
                              (splitSolids ? "" : ", stages whole")
                        : std::string()) +
            ")";
        if (Status written = writeMarkdownSection(parsed.value("markdown"), title, ctx,
                                                  reproduceCommand("bench solver", parsed), body);
            !written) {
            printError(written.error().message);
            return kExitFailure;
        }
    }
    if (plotFile.is_open()) {
        PlotPanel panel{
            "rate each stage reaches against the grid", "cells", "GB/s", true, true, {}};
        static const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                        "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
        size_t colour = 0;
        for (fluid::Stage stage : fluid::stepOrder()) {
            PlotSeries series{fluid::stageName(stage), colours[colour++ % 10], {}, {}};
            for (const GridResult& r : results) {
                auto ms = r.stageMs.find(series.label);
                auto bytes = r.stageBytes.find(series.label);
                if (ms == r.stageMs.end() || bytes == r.stageBytes.end() ||
                    bytes->second.total() == 0.0 || ms->second <= 0.0)
                    continue;
                series.x.push_back(double(r.grid[0]) * r.grid[1] * r.grid[2]);
                series.y.push_back(rate(bytes->second.total(), ms->second));
            }
            if (!series.x.empty()) panel.series.push_back(series);
        }
        PlotSeries roof{"copy bandwidth", "#000000", {}, {}};
        for (const GridResult& r : results) {
            roof.x.push_back(double(r.grid[0]) * r.grid[1] * r.grid[2]);
            roof.y.push_back(copy.gigabytesPerSecond);
        }
        panel.series.push_back(roof);
        plotFile << svgPlot("smoke solver roofline on " + ctx.info().name, {panel});
    }

    if (jsonFile.is_open()) {
        nlohmann::json list = nlohmann::json::array();
        for (const GridResult& r : results) {
            nlohmann::json stages = nlohmann::json::object();
            for (const auto& [name, ms] : r.stageMs) {
                auto bytes = r.stageBytes.find(name);
                const double total = bytes == r.stageBytes.end() ? 0.0 : bytes->second.total();
                stages[name] = {{"ms", ms},
                                {"bytes", total},
                                {"gb_per_s", rate(total, ms)},
                                {"copy_share", copy.gigabytesPerSecond > 0.0
                                                   ? rate(total, ms) / copy.gigabytesPerSecond
                                                   : 0.0}};
            }
            list.push_back({{"grid", r.grid},
                            {"workgroup", r.workgroup},
                            {"jacobi", jacobi.value()},
                            {"pressure", fluid::pressureSolverName(*pressure)},
                            {"step_ms", r.stepMs},
                            {"wall_ms", r.wallMs},
                            {"step_bytes", r.stepBytes.total()},
                            {"dispatches", r.dispatches},
                            {"step_gb_per_s", rate(r.stepBytes.total(), r.stepMs)},
                            {"body", r.withBody},
                            {"stages", stages}});
        }
        jsonFile << nlohmann::json{{"device", ctx.info().name},
                                   {"driver", ctx.info().driverInfo},
                                   {"date", todayUtc()},
                                   {"scenario", scenarioName},
                                   {"store", direct ? "direct" : "buffer"},
                                   {"coarse_group", hierarchy ? coarse : 0u},
                                   {"brick", hierarchy ? bricks : 0u},
                                   {"coarse_cells", hierarchy ? fusedCells : 0u},
                                   {"solids", solidsName},
                                   {"body_step_ratios", bodyRatios},
                                   {"solid_lists", bodySolids && splitSolids},
                                   {"residual_in_restriction", residualFused},
                                   {"first_sweep_in_divergence", firstSweepFused},
                                   {"steps", steps.value()},
                                   {"copy",
                                    {{"bytes", copy.bytes},
                                     {"ms", copy.medianMs},
                                     {"wall_clock", copy.fromWallClock},
                                     {"gb_per_s", copy.gigabytesPerSecond}}},
                                   {"results", list}}
                        .dump(2)
                 << "\n";
    }
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
