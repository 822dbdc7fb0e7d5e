// motionfx bench frame: what one frame of a scene costs, the simulation and every drawing pass,
// at a real-time size (default: the built-in scene at 960x540 with its 48^3 smoke grid). The clip
// loops so the scene runs as long as asked; the first frames (pipeline compiles) are not timed.
// Prints a table of median GPU milliseconds per pass and the whole frame's median wall time
// (record + submit + wait, as a viewer waits for it) and frames per second; --json on request.
// With --sparse N, the same scene again with its smoke on a sparse domain of N^3 cells at the same
// cell size, in the same process: both tables, then the smoke's GPU ms a step of each and their
// ratio, memory and active bricks. The smoke's ray-march is set against the device's copy
// bandwidth measured in the same run: the bytes of the pigment volumes it reads over its time.
// With --smoke-looks, the scene again with its smoke in each look (smoke, fire, energy, cartoon),
// one after another in the same process: the smoke pass's GPU ms of each and its ratio to the
// plain smoke look's.
#include "apps/bench_report.h"
#include "apps/commands.h"
#include "apps/progress.h"

#include "core/gpu/bandwidth.h"
#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "core/scene/kinds/smoke_effect.h"
#include "render/scene_player.h"
#include "sim/scene_simulation.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

namespace mfx::app {

namespace {

// The table's row for a simulation pass: the smoke stages by their own name (every grid
// together), every effect's segment building as "trajectories", the coupling as "coupling".
std::string simulationRow(const std::string& pass) {
    const std::string stage = pass.substr(pass.rfind('/') + 1);
    if (stage == "split" || stage == "unsplit" || stage == "split-xfb") return "trajectories";
    if (stage == "segment_emitters") return "coupling";
    if (pass.rfind("smoke", 0) == 0) return "smoke/" + stage;
    return stage;
}

// One scene's frames: each pass's GPU ms per timed frame (rows, in first-appearance order), the
// whole frame's GPU and wall ms, and its smoke: GPU ms of a step (the smoke passes of a frame over
// its steps, in frames where a grid stepped), the sparse grids' active bricks, the fluid memory.
struct FrameRun {
    std::vector<std::string> rowOrder;
    std::map<std::string, std::vector<double>> rows;
    std::vector<double> frameWall, frameGpu, smokeStepMs, activeBricks;
    std::vector<double> marchBytes; // the pigment volumes the smoke pass read, per timed frame
    uint64_t fluidBytes = 0;        // the largest of any frame
    std::array<uint32_t, 3> grid{0, 0, 0};
    uint32_t stepsPerFrame = 0;
    bool sparse = false;
    uint32_t samples = 0;
};

FrameRun runFrames(const gpu::Context& ctx, sim::SceneSimulation& sim, uint32_t warmup,
                   uint32_t samples, render::SmokeMarch march, const char* label) {
    const scene::Scene& s = sim.scene();
    render::ScenePlayer player(ctx, sim, s.output.width, s.output.height,
                               VkSampleCountFlagBits(samples));
    render::SmokeLook look;
    look.march = march;
    player.renderer().setSmokeLook(look);
    FrameRun run;
    run.samples = uint32_t(player.renderer().sceneTarget().samples);
    if (!sim.smokeGrids().empty()) {
        const fluid::SmokeGrid& g = sim.smokeGrids().front().grid;
        run.grid = {g.options().grid.cellsX, g.options().grid.cellsY, g.options().grid.cellsZ};
        run.stepsPerFrame = g.settings().stepsPerFrame;
        run.sparse = g.sparse();
    }
    Progress progress(label, sim.frameCount());
    for (uint32_t f = 0; f < sim.frameCount(); ++f) {
        const auto start = std::chrono::steady_clock::now();
        const sim::SimulationFrameStats stats = player.play(f);
        reportBudget(stats);
        const double wall =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        progress.update(f + 1);
        if (f < warmup) continue;
        std::map<std::string, double> frame;
        double gpu = 0.0, smoke = 0.0;
        auto add = [&](const std::string& name, double ms) {
            if (!run.rows.count(name) && !frame.count(name))
                run.rowOrder.push_back(name); // pass order
            frame[name] += ms;
            gpu += ms;
        };
        for (const sim::PassRecord& p : stats.passes) { // the drawing's as "render/<pass>"
            const std::string row =
                p.name.rfind("render/", 0) == 0 ? p.name : simulationRow(p.name);
            add(row, p.gpuMs);
            if (row.rfind("smoke/", 0) == 0) smoke += p.gpuMs;
        }
        // A pass missing from some frames (a grid asleep) counts 0 there.
        const size_t timedSoFar = run.frameWall.size();
        for (const std::string& name : run.rowOrder) {
            std::vector<double>& series = run.rows[name];
            series.resize(timedSoFar, 0.0);
            series.push_back(frame.count(name) ? frame[name] : 0.0);
        }
        run.frameWall.push_back(wall);
        run.frameGpu.push_back(gpu);
        if (stats.awakeGrids > 0 && run.stepsPerFrame > 0)
            run.smokeStepMs.push_back(smoke / double(run.stepsPerFrame));
        for (const sim::GridFrameState& g : stats.grids)
            if (g.sparse && g.awake) run.activeBricks.push_back(double(g.activeBricks));
        run.fluidBytes = std::max(run.fluidBytes, stats.fluidBytes);
        double volumes = 0.0;
        for (const sim::SceneSimulation::SmokeGrid& g : sim.smokeGrids())
            volumes += double(g.grid.pigmentVolume().bytes);
        run.marchBytes.push_back(volumes);
    }
    progress.finish();
    return run;
}

// The smoke pass's rate: the pigment volumes' bytes over the median time of the whole pass (its
// bounds search, light march and ray-march together; 0 without smoke): a lower bound of the
// ray-march's own.
double marchRate(const FrameRun& run) {
    auto smoke = run.rows.find("render/smoke");
    if (smoke == run.rows.end()) return 0.0;
    const double ms = median(smoke->second);
    return ms > 0.0 ? median(run.marchBytes) / (ms * 1e6) : 0.0;
}

void printRun(const gpu::Context& ctx, const scene::Scene& s, const FrameRun& run, uint32_t timed,
              uint32_t warmup, const gpu::CopyBandwidth& copy, MarkdownTable* table) {
    const double gpuMs = median(run.frameGpu), wallMs = median(run.frameWall);
    std::printf("frame benchmark on %s (%s)\n%s at %ux%u, %u samples per pixel, smoke grid "
                "%ux%ux%u%s (%u steps per frame); median of %u frames after %u warm-up frames\n\n",
                ctx.info().name.c_str(), ctx.info().driverInfo.c_str(), s.file.c_str(),
                s.output.width, s.output.height, run.samples, run.grid[0], run.grid[1], run.grid[2],
                run.sparse ? " sparse" : "", run.stepsPerFrame, timed, warmup);
    std::printf("%-32s %10s %8s\n", "pass", "GPU ms", "share");
    for (const std::string& name : run.rowOrder) {
        const double ms = median(run.rows.at(name));
        std::printf("%-32s %10.2f %7.1f%%\n", name.c_str(), ms, gpuMs > 0 ? 100.0 * ms / gpuMs : 0);
    }
    std::printf("%-32s %10.2f\n", "GPU, whole frame", gpuMs);
    std::printf("%-32s %10.2f   (%.1f frames per second)\n", "wall, whole frame", wallMs,
                1000.0 / wallMs);
    const double march = marchRate(run);
    if (march > 0.0)
        std::printf("smoke pass: %.2f MiB of pigment volume read at %.1f GB/s (bounds, light and "
                    "march together), %.0f%% of the copy bandwidth (%.1f GB/s%s)\n",
                    median(run.marchBytes) / (1 << 20), march,
                    copy.gigabytesPerSecond > 0 ? 100.0 * march / copy.gigabytesPerSecond : 0.0,
                    copy.gigabytesPerSecond, copy.fromWallClock ? ", wall clock" : "");
    if (table) {
        table->header = {"pass", "GPU ms", "share"};
        for (const std::string& name : run.rowOrder) {
            const double ms = median(run.rows.at(name));
            table->rows.push_back(
                {name, fixed(ms, 2), fixed(gpuMs > 0 ? 100.0 * ms / gpuMs : 0, 1) + "%"});
        }
        table->rows.push_back({"**GPU, whole frame**", "**" + fixed(gpuMs, 2) + "**", ""});
        table->rows.push_back({"**wall, whole frame**", "**" + fixed(wallMs, 2) + "**",
                               fixed(1000.0 / wallMs, 1) + " fps"});
        if (march > 0.0)
            table->rows.push_back(
                {"smoke pass rate (pigment bytes / render/smoke: bounds, light, march)",
                 fixed(march, 1) + " GB/s",
                 fixed(copy.gigabytesPerSecond > 0 ? 100.0 * march / copy.gigabytesPerSecond : 0,
                       0) +
                     "% of copy" + (copy.fromWallClock ? " (wall clock)" : "")});
    }
}

nlohmann::json runJson(const FrameRun& run) {
    nlohmann::json passes = nlohmann::json::object();
    for (const std::string& name : run.rowOrder)
        passes[name] = median(run.rows.at(name));
    const double wallMs = median(run.frameWall);
    nlohmann::json j = {{"grid", run.grid},
                        {"sparse", run.sparse},
                        {"steps_per_frame", run.stepsPerFrame},
                        {"samples", run.samples},
                        {"frame_ms", wallMs},
                        {"gpu_ms", median(run.frameGpu)},
                        {"fps", 1000.0 / wallMs},
                        {"smoke_step_ms", median(run.smokeStepMs)},
                        {"fluid_bytes", run.fluidBytes},
                        {"march_bytes", median(run.marchBytes)},
                        {"march_gb_per_s", marchRate(run)},
                        {"passes", passes}};
    if (run.sparse) j["active_bricks"] = median(run.activeBricks);
    return j;
}

// The scene with every smoke effect on a sparse domain of `cells`^3 at its own cell size. A solver
// option the sparse domain does not have is refused by name when its grid is made
// (validateSparseOptions, through createSceneSimulation).
scene::Scene sparseScene(scene::Scene s, uint32_t cells) {
    for (scene::EffectSpec& e : s.effects)
        if (scene::SmokeSpec* smoke = e.as<scene::SmokeSpec>()) {
            smoke->grid.domain = "sparse";
            smoke->grid.cells = {cells, cells, cells};
            smoke->grid.follow = false;
        }
    return s;
}

// The scene with every smoke effect in look `preset` (its defaults).
scene::Scene lookScene(scene::Scene s, scene::SmokePreset preset) {
    for (scene::EffectSpec& e : s.effects)
        if (scene::SmokeSpec* smoke = e.as<scene::SmokeSpec>())
            smoke->shading = scene::smokeShading(preset);
    return s;
}

// The smoke pass of the scene in each look, run after one another; a table and its JSON.
Result<nlohmann::json> compareSmokeLooks(const gpu::Context& ctx, const SceneArgument& argument,
                                         uint32_t warmup, uint32_t samples,
                                         render::SmokeMarch march) {
    struct Look {
        const char* name;
        scene::SmokePreset preset;
    };
    const Look looks[] = {{"smoke", scene::SmokePreset::Smoke},
                          {"fire", scene::SmokePreset::Fire},
                          {"energy", scene::SmokePreset::Energy},
                          {"cartoon", scene::SmokePreset::Cartoon}};
    nlohmann::json out = nlohmann::json::object();
    std::printf("\nthe smoke pass (render/smoke: bounds, light, march, composite) in each look, "
                "same run\n%-10s %14s %14s %16s\n",
                "look", "smoke GPU ms", "frame GPU ms", "smoke / smoke's");
    double plain = 0.0;
    for (const Look& look : looks) {
        SceneArgument variant;
        variant.scene = lookScene(argument.scene, look.preset);
        variant.cast = argument.cast;
        int exitCode = kExitOk;
        const std::unique_ptr<sim::SceneSimulation> sim =
            createSceneSimulation(ctx, variant, exitCode);
        if (!sim) return Error{std::string("the scene in look ") + look.name + " did not start"};
        const FrameRun run = runFrames(ctx, *sim, warmup, samples, march,
                                       (std::string("benchmarking look ") + look.name).c_str());
        const auto smoke = run.rows.find("render/smoke");
        const double ms = smoke == run.rows.end() ? 0.0 : median(smoke->second);
        if (look.preset == scene::SmokePreset::Smoke) plain = ms;
        const double ratio = plain > 0.0 ? ms / plain : 0.0;
        std::printf("%-10s %14.2f %14.2f %16.2f\n", look.name, ms, median(run.frameGpu), ratio);
        out[look.name] = {{"smoke_ms", ms},
                          {"gpu_ms", median(run.frameGpu)},
                          {"over_smoke_look", ratio}};
    }
    return out;
}

} // namespace

int runBenchFrame(const cli::ParsedArgs& parsed) {
    auto timed = cli::parseUnsigned(parsed.value("frames", "60"), 1, 100000, "--frames");
    auto warmup = cli::parseUnsigned(parsed.value("warmup", "5"), 0, 1000, "--warmup");
    auto sparseCells = cli::parseUnsigned(parsed.value("sparse", "0"), 0, 2048, "--sparse");
    const Result<uint32_t> samples = parseSamples(parsed);
    if (reportFirstError(timed, warmup, sparseCells, samples)) return kExitUsage;
    const std::string marchName = parsed.value("smoke-march", "auto");
    const std::optional<render::SmokeMarch> march =
        marchName == "auto"       ? std::optional(render::SmokeMarch::Auto)
        : marchName == "fragment" ? std::optional(render::SmokeMarch::Fragment)
        : marchName == "compute"  ? std::optional(render::SmokeMarch::Compute)
                                  : std::nullopt;
    if (!march) {
        printError("--smoke-march must be auto, fragment or compute, not \"" + marchName + "\"");
        return kExitUsage;
    }
    if (sparseCells.value() % 8 != 0) {
        printError("--sparse: " + std::to_string(sparseCells.value()) +
                   " is not a multiple of 8 (the sparse domain's bricks are 8 cells a side)");
        return kExitUsage;
    }
    cli::ParsedArgs sceneArgs = parsed;
    sceneArgs.values.erase("frames"); // --frames counts timed frames here
    SceneArgument argument;
    int exitCode = kExitOk;
    if (!loadSceneArgument(sceneArgs, argument, exitCode, "960x540")) return exitCode;
    scene::Scene& s = argument.scene;
    for (scene::CharacterSpec& c : s.characters)
        c.loop = true;
    s.output.frames = warmup.value() + timed.value();
    SceneArgument sparseArgument;
    if (sparseCells.value() > 0) {
        sparseArgument.scene = sparseScene(s, sparseCells.value());
        sparseArgument.cast = argument.cast;
    }
    std::ofstream jsonFile;
    if (!openOutputFile(parsed.value("json"), jsonFile)) return kExitFailure;
    if (parsed.has("markdown"))
        if (Status ok = checkMarkdownFile(parsed.value("markdown")); !ok) {
            printError(ok.error().message);
            return kExitFailure;
        }

    const std::unique_ptr<gpu::Context> context = createTimingContext(parsed, "the passes");
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    // Both simulations made before either runs, so a scene the sparse domain cannot run is
    // refused at once (the idle one's memory does not change the other's timings).
    const std::unique_ptr<sim::SceneSimulation> dense =
        createSceneSimulation(ctx, argument, exitCode);
    if (!dense) return exitCode;
    std::unique_ptr<sim::SceneSimulation> sparse;
    if (sparseCells.value() > 0) {
        sparse = createSceneSimulation(ctx, sparseArgument, exitCode);
        if (!sparse) return exitCode;
    }
    const FrameRun run =
        runFrames(ctx, *dense, warmup.value(), samples.value(), *march, "benchmarking");
    // The yardstick after the frames (a GPU has left its idle clock by then).
    const gpu::CopyBandwidth copy = gpu::measureCopyBandwidth(
        ctx, std::min<uint64_t>(uint64_t(256) << 20, ctx.limits().maxStorageBufferRange));
    MarkdownTable table;
    printRun(ctx, s, run, timed.value(), warmup.value(), copy, &table);
    nlohmann::json json = runJson(run);
    json["device"] = ctx.info().name;
    json["driver"] = ctx.info().driverInfo;
    json["scene"] = s.file;
    json["size"] = {s.output.width, s.output.height};
    json["frames"] = timed.value();
    json["date"] = todayUtc();
    json["copy_gb_per_s"] = copy.gigabytesPerSecond;
    json["copy_wall_clock"] = copy.fromWallClock;
    if (sparse) {
        const FrameRun sparseRun = runFrames(ctx, *sparse, warmup.value(), samples.value(), *march,
                                             "benchmarking the sparse domain");
        std::printf("\n");
        printRun(ctx, sparseArgument.scene, sparseRun, timed.value(), warmup.value(), copy,
                 nullptr);
        // The smoke's cost a step, dense as the scene has it against the sparse domain, same run.
        const double denseStep = median(run.smokeStepMs),
                     sparseStep = median(sparseRun.smokeStepMs);
        const double mib = 1.0 / (1024.0 * 1024.0);
        std::printf(
            "\nsmoke a step (every smoke pass of a frame over its steps, frames with a grid "
            "awake), same run\n");
        std::printf("%-26s %14s %14s\n", "", "dense", "sparse");
        std::printf("%-26s %14s %14s\n", "grid",
                    (std::to_string(run.grid[0]) + "x" + std::to_string(run.grid[1]) + "x" +
                     std::to_string(run.grid[2]))
                        .c_str(),
                    (std::to_string(sparseRun.grid[0]) + "^3 virtual").c_str());
        std::printf("%-26s %14.3f %14.3f\n", "GPU ms a step (median)", denseStep, sparseStep);
        std::printf("%-26s %14.1f %14.1f\n", "fluid MiB (largest)", double(run.fluidBytes) * mib,
                    double(sparseRun.fluidBytes) * mib);
        std::printf("%-26s %14s %14.0f\n", "active bricks (median)", "-",
                    median(sparseRun.activeBricks));
        std::printf("sparse / dense: %.2f a step\n", denseStep > 0 ? sparseStep / denseStep : 0.0);
        json["sparse_run"] = runJson(sparseRun);
        json["sparse_over_dense_step"] = denseStep > 0 ? sparseStep / denseStep : 0.0;
    }
    if (parsed.has("smoke-looks")) {
        Result<nlohmann::json> looks =
            compareSmokeLooks(ctx, argument, warmup.value(), samples.value(), *march);
        if (!looks.ok()) {
            printError(looks.error().message);
            return kExitFailure;
        }
        json["smoke_looks"] = looks.value();
    }
    if (jsonFile.is_open()) jsonFile << json.dump(2) << "\n";
    if (parsed.has("markdown")) {
        const std::string title =
            "Frame, " + s.file + " at " + std::to_string(s.output.width) + "x" +
            std::to_string(s.output.height) + ", " + std::to_string(run.samples) + " samples" +
            (*march == render::SmokeMarch::Auto ? std::string()
                                                : ", " + marchName + " smoke march");
        if (Status written =
                writeMarkdownSection(parsed.value("markdown"), title, ctx,
                                     reproduceCommand("bench frame", parsed), table.text());
            !written) {
            printError(written.error().message);
            return kExitFailure;
        }
    }
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
