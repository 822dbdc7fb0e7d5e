// motionfx bench frame: what one frame of a scene costs, the simulation and every drawing pass,
// at a real-time size (default: the built-in scene at 960x540 with its 48^3 smoke grid). The clip
// loops so the scene runs as long as asked; the first frames (pipeline compiles) are not timed.
// Prints a table of median GPU milliseconds per pass and the whole frame's median wall time
// (record + submit + wait, as a viewer waits for it) and frames per second; --json on request.
#include "apps/commands.h"
#include "apps/progress.h"

#include "core/gpu/commands.h"
#include "render/scene_player.h"
#include "sim/scene_simulation.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

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

} // namespace

int runBenchFrame(const cli::ParsedArgs& parsed) {
    auto timed = cli::parseUnsigned(parsed.value("frames", "60"), 1, 100000, "--frames");
    auto warmup = cli::parseUnsigned(parsed.value("warmup", "5"), 0, 1000, "--warmup");
    const Result<uint32_t> samples = parseSamples(parsed);
    if (reportFirstError(timed, warmup, samples)) return kExitUsage;
    cli::ParsedArgs sceneArgs = parsed;
    sceneArgs.values.erase("frames"); // --frames counts timed frames here
    SceneArgument argument;
    int exitCode = kExitOk;
    if (!loadSceneArgument(sceneArgs, argument, exitCode, "960x540")) return exitCode;
    scene::Scene& s = argument.scene;
    s.character.loop = true;
    s.output.frames = warmup.value() + timed.value();
    std::ofstream jsonFile;
    if (!openOutputFile(parsed.value("json"), jsonFile)) return kExitFailure;

    const std::unique_ptr<gpu::Context> context = createTimingContext(parsed, "the passes");
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    const std::unique_ptr<sim::SceneSimulation> created =
        createSceneSimulation(ctx, argument, exitCode);
    if (!created) return exitCode;
    sim::SceneSimulation& sim = *created;
    render::ScenePlayer player(ctx, sim, s.output.width, s.output.height,
                               VkSampleCountFlagBits(samples.value()));

    std::vector<std::string> rowOrder; // first appearance
    std::map<std::string, std::vector<double>> rows;
    std::vector<double> frameWall, frameGpu;
    Progress progress("benchmarking", sim.frameCount());
    for (uint32_t f = 0; f < sim.frameCount(); ++f) {
        const auto start = std::chrono::steady_clock::now();
        const sim::SimulationFrameStats stats = player.play(f);
        reportBudget(stats);
        const double wall =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        progress.update(f + 1);
        if (f < warmup.value()) continue;
        std::map<std::string, double> frame;
        double gpu = 0.0;
        auto add = [&](const std::string& name, double ms) {
            if (!rows.count(name) && !frame.count(name)) rowOrder.push_back(name); // pass order
            frame[name] += ms;
            gpu += ms;
        };
        for (const sim::PassRecord& p : stats.passes) // the drawing's as "render/<pass>"
            add(p.name.rfind("render/", 0) == 0 ? p.name : simulationRow(p.name), p.gpuMs);
        // A pass missing from some frames (a grid asleep) counts 0 there.
        const size_t timedSoFar = frameWall.size();
        for (const std::string& name : rowOrder) {
            std::vector<double>& series = rows[name];
            series.resize(timedSoFar, 0.0);
            series.push_back(frame.count(name) ? frame[name] : 0.0);
        }
        frameWall.push_back(wall);
        frameGpu.push_back(gpu);
    }
    progress.finish();

    const double wallMs = median(frameWall), gpuMs = median(frameGpu);
    std::array<uint32_t, 3> grid{0, 0, 0};
    uint32_t stepsPerFrame = 0;
    if (!sim.smokeGrids().empty()) {
        const fluid::GridShape& g = sim.smokeGrids().front().grid.options().grid;
        grid = {g.cellsX, g.cellsY, g.cellsZ};
        stepsPerFrame = sim.smokeGrids().front().grid.settings().stepsPerFrame;
    }
    std::printf("frame benchmark on %s (%s)\n%s at %ux%u, %u samples per pixel, smoke grid "
                "%ux%ux%u (%u steps per frame); median of %u frames after %u warm-up frames\n\n",
                ctx.info().name.c_str(), ctx.info().driverInfo.c_str(), s.file.c_str(),
                s.output.width, s.output.height, uint32_t(player.renderer().sceneTarget().samples),
                grid[0], grid[1], grid[2], stepsPerFrame, timed.value(), warmup.value());
    std::printf("%-32s %10s %8s\n", "pass", "GPU ms", "share");
    nlohmann::json passes = nlohmann::json::object();
    for (const std::string& name : rowOrder) {
        const double ms = median(rows[name]);
        passes[name] = ms;
        std::printf("%-32s %10.2f %7.1f%%\n", name.c_str(), ms, gpuMs > 0 ? 100.0 * ms / gpuMs : 0);
    }
    std::printf("%-32s %10.2f\n", "GPU, whole frame", gpuMs);
    std::printf("%-32s %10.2f   (%.1f frames per second)\n", "wall, whole frame", wallMs,
                1000.0 / wallMs);
    if (jsonFile.is_open())
        jsonFile << nlohmann::json{{"device", ctx.info().name},
                                   {"driver", ctx.info().driverInfo},
                                   {"scene", s.file},
                                   {"size", {s.output.width, s.output.height}},
                                   {"grid", grid},
                                   {"steps_per_frame", stepsPerFrame},
                                   {"samples", uint32_t(player.renderer().sceneTarget().samples)},
                                   {"frames", timed.value()},
                                   {"frame_ms", wallMs},
                                   {"gpu_ms", gpuMs},
                                   {"fps", 1000.0 / wallMs},
                                   {"passes", passes}}
                        .dump(2)
                 << "\n";
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
