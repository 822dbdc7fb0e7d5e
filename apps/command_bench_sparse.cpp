// motionfx bench solver --domain sparse: what a step of the sparse smoke grid costs
// (fluid/sparse_smoke_solver.h) against the number of active bricks, in a virtual domain of
// --virtual cells a side, and a dense grid of the same cells in the same run. A benchmark program:
// it prints a table and writes a plot, never passes or fails on time.
#include "apps/commands.h"
#include "apps/svg_plot.h"

#include "core/gpu/commands.h"
#include "core/gpu/timer.h"
#include "fluid/smoke_solver.h"
#include "fluid/sparse_smoke_solver.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

namespace mfx::app {

namespace {

struct SparseResult {
    uint32_t bricks = 0;    // active
    double stepMs = 0.0;    // median GPU ms of a step (its stages)
    double rebuildMs = 0.0; // median GPU ms of the active set's rebuild
    double denseMs = 0.0;   // a dense grid of the block's cells, same run
    uint64_t bytes = 0;     // the sparse solver's GPU memory
    uint64_t denseBytes = 0;
    std::map<std::string, double> stageMs;
};

Result<std::vector<uint32_t>> parseCounts(const std::string& text) {
    std::vector<uint32_t> counts;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        auto n = cli::parseUnsigned(item, 1, 1u << 20, "--bricks");
        if (!n) return n.error();
        counts.push_back(n.value());
    }
    if (counts.empty()) return Error{"--bricks needs at least one count, e.g. 8,64,512"};
    return counts;
}

// The solver options of the benchmark: a rising puff's, open on every side but the floor (the
// scene's smoke), Jacobi, no vorticity confinement (the sparse domain has none yet).
fluid::SolverOptions benchOptions(uint32_t cells, float cellSize, uint32_t jacobi) {
    fluid::SolverOptions o;
    o.grid = {cells, cells, cells, cellSize};
    o.dt = 1.0f / 60.0f;
    o.integrator = fluid::Integrator::RK2;
    o.buoyancy = 2.0f;
    o.fade = 0.1f;
    o.drag = 0.2f;
    o.jacobiIterations = jacobi;
    for (fluid::FaceBoundary& face : o.boundaries)
        face.kind = fluid::Boundary::Open;
    o.boundaries[fluid::FaceLowY].kind = fluid::Boundary::WallFreeSlip;
    return o;
}

// The first `count` bricks of a cube of bricks (x fastest) centred in the domain.
std::vector<glm::ivec3> brickBlock(uint32_t count, glm::uvec3 domain) {
    const int side = int(std::ceil(std::cbrt(double(count)) - 1e-9));
    const glm::ivec3 low = glm::ivec3(domain) / 2 - side / 2;
    std::vector<glm::ivec3> block;
    for (int z = 0; z < side && block.size() < count; ++z)
        for (int y = 0; y < side && block.size() < count; ++y)
            for (int x = 0; x < side && block.size() < count; ++x)
                block.push_back(low + glm::ivec3(x, y, z));
    return block;
}

// Times `steps` steps after 3 warm-up steps: record (with `timer`), submit, wait.
template <typename Record>
std::vector<double> timeSteps(const gpu::Context& ctx, gpu::GpuTimer& timer, uint32_t steps,
                              Record record,
                              std::map<std::string, std::vector<double>>* stages = nullptr) {
    std::vector<double> totals;
    for (uint32_t step = 0; step < 3 + steps; ++step) {
        gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
            timer.reset(cmd);
            record(cmd);
        });
        if (step < 3) continue;
        double total = 0.0;
        std::map<std::string, double> perStage;
        for (const gpu::PassTime& pass : timer.results()) {
            perStage[pass.name] += pass.milliseconds;
            total += pass.milliseconds;
        }
        if (stages)
            for (const auto& [name, ms] : perStage)
                (*stages)[name].push_back(ms);
        totals.push_back(total);
    }
    return totals;
}

Result<SparseResult> benchBricks(const gpu::Context& ctx, uint32_t virtualCells, uint32_t count,
                                 uint32_t jacobi, uint32_t steps) {
    const float h = 1.0f / float(virtualCells);
    const fluid::SolverOptions o = benchOptions(virtualCells, h, jacobi);
    auto made = fluid::SparseSmokeSolver::create(ctx, o, count, count);
    if (!made) return made.error();
    fluid::SparseSmokeSolver& sparse = *made.value();
    const std::vector<glm::ivec3> block = brickBlock(count, sparse.layout().bricks());
    sparse.layout().clearWanted();
    glm::vec3 low(1e9f), high(-1e9f);
    for (glm::ivec3 b : block) {
        sparse.layout().wantCell(b * int(fluid::kBrickSize));
        low = glm::min(low, glm::vec3(b));
        high = glm::max(high, glm::vec3(b + 1));
    }
    const auto update = sparse.commitActive();
    if (update.refused > 0) return Error{"the benchmark's block did not fit its budget"};
    // One emitter at the block's centre, as wide as the block: every stage has work.
    const float brickWorld = float(fluid::kBrickSize) * h;
    const glm::vec3 centre = 0.5f * (low + high) * brickWorld;
    const float radius = 0.5f * glm::length(high - low) * brickWorld * 0.5f;
    const shared::FluidEmitter emitter{glm::vec4(centre, radius),
                                       glm::vec4(0.0f, 1.5f, 0.0f, 30.0f),
                                       glm::vec4(1.0f, 0.55f, 0.15f, 1.0f)};
    if (Status ok = sparse.setEmitters({&emitter, 1}); !ok) return ok.error();

    SparseResult r;
    r.bricks = uint32_t(block.size());
    gpu::GpuTimer timer(ctx, sparse.passesPerStep() + 1);
    std::map<std::string, std::vector<double>> stages;
    r.stepMs = median(timeSteps(
        ctx, timer, steps, [&](VkCommandBuffer cmd) { sparse.recordStep(cmd, &timer); }, &stages));
    for (const auto& [name, times] : stages)
        r.stageMs[name] = median(times);
    // The rebuild alone, with every cell counted live and no dilation: the set stays the block.
    r.rebuildMs = median(timeSteps(ctx, timer, steps, [&](VkCommandBuffer cmd) {
        timer.begin(cmd, "rebuild");
        sparse.recordRebuild(cmd, -1.0f, -1.0f, 0);
        timer.end(cmd);
    }));
    r.bytes = sparse.memoryBytes();

    // A dense grid of the same cells (the block's box), same options.
    const glm::uvec3 cells = glm::uvec3(high - low) * fluid::kBrickSize;
    fluid::SolverOptions d = o;
    d.grid = {cells.x, cells.y, cells.z, h};
    auto dense = fluid::SmokeSolver::create(ctx, d);
    if (!dense) return dense.error();
    shared::FluidEmitter local = emitter;
    local.positionRadius = glm::vec4(glm::vec3(cells) * 0.5f * h, radius);
    if (Status ok = dense.value()->setEmitters({&local, 1}); !ok) return ok.error();
    gpu::GpuTimer denseTimer(ctx, dense.value()->passesPerStep());
    r.denseMs = median(timeSteps(ctx, denseTimer, steps, [&](VkCommandBuffer cmd) {
        dense.value()->recordStep(cmd, &denseTimer);
    }));
    r.denseBytes = dense.value()->memoryBytes();
    return r;
}

} // namespace

int runBenchSparse(const cli::ParsedArgs& parsed) {
    auto virtualCells = cli::parseUnsigned(parsed.value("virtual", "256"), 8, 4096, "--virtual");
    auto counts = parseCounts(parsed.value("bricks", "8,27,64,125,216,343,512,729,1000"));
    auto jacobi = cli::parseUnsigned(parsed.value("jacobi", "20"), 0, 100000, "--jacobi");
    auto steps = cli::parseUnsigned(parsed.value("steps", "10"), 1, 10000, "--steps");
    if (reportFirstError(virtualCells, counts, jacobi, steps)) return kExitUsage;
    if (virtualCells.value() % fluid::kBrickSize != 0) {
        printError("--virtual must be a multiple of 8 (the brick size), not " +
                   std::to_string(virtualCells.value()));
        return kExitUsage;
    }
    const uint64_t domainBricks = uint64_t(virtualCells.value() / fluid::kBrickSize) *
                                  (virtualCells.value() / fluid::kBrickSize) *
                                  (virtualCells.value() / fluid::kBrickSize);
    for (uint32_t c : counts.value())
        if (c > domainBricks) {
            printError("--bricks: " + std::to_string(c) + " is more than the " +
                       std::to_string(domainBricks) + " bricks of a " +
                       std::to_string(virtualCells.value()) + "³ domain");
            return kExitUsage;
        }
    std::ofstream jsonFile, plotFile;
    if (!openOutputFile(parsed.value("json"), jsonFile)) return kExitFailure;
    if (!openOutputFile(parsed.value("plot"), plotFile)) return kExitFailure;
    const std::unique_ptr<gpu::Context> context = createTimingContext(parsed, "the solver");
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    const uint32_t v = virtualCells.value();
    std::printf("sparse smoke solver benchmark on %s (%s)\nvirtual domain %u³ (%llu bricks of "
                "8³), a block of active bricks at its centre with a puff in it, %u Jacobi "
                "sweeps, median of %u steps after 3 warm-up steps; GPU milliseconds from "
                "timestamp queries; the dense grid is the block's box, same run\n\n",
                ctx.info().name.c_str(), ctx.info().driverInfo.c_str(), v,
                static_cast<unsigned long long>(domainBricks), jacobi.value(), steps.value());

    std::vector<SparseResult> results;
    for (uint32_t count : counts.value()) {
        std::fprintf(stderr, "  %u bricks\n", count);
        auto r = benchBricks(ctx, v, count, jacobi.value(), steps.value());
        if (!r) {
            printError(r.error().message);
            return kExitFailure;
        }
        results.push_back(std::move(r.value()));
    }

    std::printf("%8s %10s %12s %12s %12s %10s %12s %12s\n", "bricks", "cells", "step ms",
                "ms/brick", "rebuild ms", "MiB", "dense ms", "dense MiB");
    for (const SparseResult& r : results)
        std::printf("%8u %10u %12.3f %12.5f %12.3f %10.1f %12.3f %12.1f\n", r.bricks,
                    r.bricks * 512u, r.stepMs, r.stepMs / r.bricks, r.rebuildMs,
                    double(r.bytes) / 1048576.0, r.denseMs, double(r.denseBytes) / 1048576.0);
    // Least-squares line through (bricks, ms): cost = a + b bricks, and how well it fits.
    double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    const double n = double(results.size());
    for (const SparseResult& r : results) {
        sx += r.bricks;
        sy += r.stepMs;
        sxx += double(r.bricks) * r.bricks;
        sxy += r.bricks * r.stepMs;
        syy += r.stepMs * r.stepMs;
    }
    const double denom = n * sxx - sx * sx;
    const double slope = denom != 0.0 ? (n * sxy - sx * sy) / denom : 0.0;
    const double intercept = (sy - slope * sx) / n;
    const double r2num = n * sxy - sx * sy;
    const double r2den = (n * sxx - sx * sx) * (n * syy - sy * sy);
    const double r2 = r2den > 0.0 ? r2num * r2num / r2den : 1.0;
    std::printf("\nlinear fit: step ms = %.4f + %.5f x bricks (R² = %.4f)\n", intercept, slope, r2);

    if (plotFile.is_open()) {
        PlotPanel panel{"a step against the active bricks",
                        "active bricks (8³ cells each)",
                        "GPU ms a step",
                        false,
                        false,
                        {}};
        PlotSeries sparseSeries{"sparse (" + std::to_string(v) + "³ virtual)", "#1f77b4", {}, {}};
        PlotSeries denseSeries{"dense, the block's box", "#ff7f0e", {}, {}};
        PlotSeries fit{"linear fit", "#7f7f7f", {}, {}};
        for (const SparseResult& r : results) {
            sparseSeries.x.push_back(r.bricks);
            sparseSeries.y.push_back(r.stepMs);
            denseSeries.x.push_back(r.bricks);
            denseSeries.y.push_back(r.denseMs);
            fit.x.push_back(r.bricks);
            fit.y.push_back(intercept + slope * r.bricks);
        }
        panel.series = {sparseSeries, denseSeries, fit};
        plotFile << svgPlot("sparse smoke solver on " + ctx.info().name, {panel});
    }
    if (jsonFile.is_open()) {
        nlohmann::json list = nlohmann::json::array();
        for (const SparseResult& r : results)
            list.push_back({{"bricks", r.bricks},
                            {"step_ms", r.stepMs},
                            {"rebuild_ms", r.rebuildMs},
                            {"bytes", r.bytes},
                            {"dense_step_ms", r.denseMs},
                            {"dense_bytes", r.denseBytes},
                            {"stages", r.stageMs}});
        jsonFile
            << nlohmann::json{{"device", ctx.info().name},
                              {"driver", ctx.info().driverInfo},
                              {"virtual", v},
                              {"jacobi", jacobi.value()},
                              {"steps", steps.value()},
                              {"fit",
                               {{"intercept_ms", intercept}, {"ms_per_brick", slope}, {"r2", r2}}},
                              {"results", list}}
                   .dump(2)
            << "\n";
    }
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
