// motionfx simulate: runs a scene's motion and smoke on the GPU without drawing it, frame by frame
// as a render would, and reports what ran (--stats FILE: every pass with its dispatches and GPU
// milliseconds, and the fluid memory, per frame).
#include "apps/commands.h"
#include "apps/progress.h"

#include "sim/scene_simulation.h"

#include <cstdio>
#include <nlohmann/json.hpp>

namespace mfx::app {

nlohmann::json statsJson(const sim::SimulationFrameStats& s) {
    nlohmann::json passes = nlohmann::json::array();
    for (const sim::PassRecord& p : s.passes)
        passes.push_back({{"name", p.name}, {"dispatches", p.dispatches}, {"gpu_ms", p.gpuMs}});
    nlohmann::json grids = nlohmann::json::array();
    for (const sim::GridFrameState& g : s.grids) {
        nlohmann::json grid = {{"name", g.name}, {"awake", g.awake}, {"emitters", g.emitters}};
        if (g.sparse) {
            grid["active_bricks"] = g.activeBricks;
            grid["refused_bricks"] = g.refusedBricks;
        }
        if (g.solids > 0) {
            grid["solids"] = g.solids;
            grid["solid_cells"] = g.solidCells;
        }
        if (g.measured) {
            grid["largest_alpha"] = g.largestAlpha;
            grid["largest_speed"] = g.largestSpeed;
        }
        grids.push_back(grid);
    }
    return {{"frame", s.frame},
            {"time", s.time},
            {"passes", passes},
            {"fluid_bytes", s.fluidBytes},
            {"dispatches", s.dispatches()},
            {"grids", grids}};
}

int runSimulate(const cli::ParsedArgs& parsed) {
    SceneArgument argument;
    int exitCode = kExitOk;
    if (!loadSceneArgument(parsed, argument, exitCode)) return exitCode;
    const scene::Scene& s = argument.scene;
    std::ofstream statsFile;
    if (!openOutputFile(parsed.value("stats"), statsFile)) return kExitFailure;
    VdbOutput vdb;
    if (!readVdbOutput(parsed, vdb)) return kExitFailure;
    const std::unique_ptr<gpu::Context> context = createContext(parsed);
    if (!context) return kExitFailure;
    auto created = sim::SceneSimulation::create(*context, s, argument.cast);
    if (!created) {
        printError(created.error().message);
        return kExitFailure;
    }
    sim::SceneSimulation& sim = *created.value();
    Progress progress("simulating", sim.frameCount());
    nlohmann::json frames = nlohmann::json::array();
    double gpuTotal = 0.0;
    uint32_t dispatchTotal = 0, sleepingFrames = 0;
    for (uint32_t f = 0; f < sim.frameCount(); ++f) {
        const sim::SimulationFrameStats stats = sim.runFrame(f);
        reportBudget(stats);
        double gpu = 0.0;
        for (const sim::PassRecord& p : stats.passes)
            gpu += p.gpuMs;
        gpuTotal += gpu;
        dispatchTotal += stats.dispatches();
        if (!sim.smokeGrids().empty() && stats.awakeGrids == 0) ++sleepingFrames;
        frames.push_back(statsJson(stats));
        if (Status written = writeFrameVdbs(sim, f, vdb); !written) {
            printError(written.error().message);
            return kExitFailure;
        }
        char note[64];
        std::snprintf(note, sizeof note, "(%.1f ms GPU)", gpu);
        progress.update(f + 1, note);
    }
    progress.finish();
    std::printf("%s: %u frames on %s, %u dispatches, %.1f ms GPU in all; %zu trajectory effects, "
                "%zu smoke grids (%.1f MiB), asleep in %u frames\n",
                s.file.c_str(), sim.frameCount(), context->info().name.c_str(), dispatchTotal,
                gpuTotal, sim.trajectories().size(), sim.smokeGrids().size(),
                double(sim.fluidBytes()) / (1024.0 * 1024.0), sleepingFrames);
    if (vdb.on) std::printf("wrote %u OpenVDB files into %s\n", vdb.files, vdb.dir.c_str());
    reportMotionlessEffects(sim.scene(), argument.cast, sim.frameCount());
    if (statsFile.is_open())
        statsFile << nlohmann::json{{"device", context->info().name},
                                    {"scene", s.file},
                                    {"fps", s.output.fps},
                                    {"frames", frames}}
                         .dump(1)
                  << "\n";
    return finishValidation(*context, kExitOk);
}

} // namespace mfx::app
