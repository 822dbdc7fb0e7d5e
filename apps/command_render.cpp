// motionfx render: a scene (or the built-in default) rendered headless, frame by frame, into
// numbered PNGs (and an MP4 when ffmpeg is installed), with a progress bar and per-frame stats.
#include "apps/commands.h"
#include "apps/progress.h"

#include "core/gpu/commands.h"
#include "render/image_output.h"
#include "render/scene_player.h"
#include "sim/scene_simulation.h"

#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>

namespace mfx::app {

namespace {

bool haveFfmpeg() {
    return std::system("command -v ffmpeg >/dev/null 2>&1") == 0;
}

std::string frameName(uint32_t frame) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04u.png", frame);
    return name;
}

} // namespace

int runRender(const cli::ParsedArgs& parsed) {
    SceneArgument argument;
    int exitCode = kExitOk;
    if (!loadSceneArgument(parsed, argument, exitCode)) return exitCode;
    const scene::Scene& s = argument.scene;
    const std::string outDir = parsed.value("out", "out");
    // Check the outputs before the (slower) GPU work, so a typo fails at once.
    if (Status dir = render::ensureOutputDirectory(outDir); !dir) {
        printError(dir.error().message);
        return kExitFailure;
    }
    std::ofstream statsFile;
    if (!openOutputFile(parsed.value("stats"), statsFile)) return kExitFailure;
    const std::unique_ptr<gpu::Context> context = createContext(parsed);
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    const std::unique_ptr<sim::SceneSimulation> created =
        createSceneSimulation(ctx, argument, exitCode);
    if (!created) return exitCode;
    sim::SceneSimulation& sim = *created;
    // 4x multisampling for anti-aliased edges (fewer where the device allows fewer).
    render::ScenePlayer player(ctx, sim, s.output.width, s.output.height);
    render::FrameRenderer& renderer = player.renderer();

    Progress progress("rendering", sim.frameCount());
    nlohmann::json frames = nlohmann::json::array();
    for (uint32_t f = 0; f < sim.frameCount(); ++f) {
        const sim::SimulationFrameStats stats = player.play(f);
        const std::vector<uint8_t> rgba = render::readColor(ctx, renderer.target());
        if (Status written = render::writePng(outDir + "/" + frameName(f), s.output.width,
                                              s.output.height, rgba);
            !written) {
            printError(written.error().message);
            return kExitFailure;
        }
        nlohmann::json record = statsJson(stats);
        record["effect_draws"] = renderer.effectDraws();
        frames.push_back(record);
        double gpu = 0.0;
        for (const sim::PassRecord& p : stats.passes)
            gpu += p.gpuMs;
        char note[64];
        std::snprintf(note, sizeof note, "(%.1f ms GPU)", gpu);
        progress.update(f + 1, note);
    }
    progress.finish();
    std::string video;
    if (haveFfmpeg()) {
        const std::string ffmpeg =
            "ffmpeg -y -loglevel error -framerate " + std::to_string(s.output.fps) + " -i \"" +
            outDir + "/frame_%04d.png\" -pix_fmt yuv420p \"" + outDir + "/scene.mp4\"";
        video = std::system(ffmpeg.c_str()) == 0 ? ", and " + outDir + "/scene.mp4"
                                                 : " (ffmpeg failed: no MP4)";
    } else {
        video = " (ffmpeg is not installed: no MP4)";
    }
    std::printf("rendered %s on %s: %u frames of %ux%u in %s/frame_0000.png ... %s%s\n",
                s.file.c_str(), ctx.info().name.c_str(), sim.frameCount(), s.output.width,
                s.output.height, outDir.c_str(), frameName(sim.frameCount() - 1).c_str(),
                video.c_str());
    reportMotionlessEffects(sim.scene(), argument.character, sim.frameCount());
    if (statsFile.is_open())
        statsFile << nlohmann::json{{"device", ctx.info().name},
                                    {"scene", s.file},
                                    {"fps", s.output.fps},
                                    {"frames", frames}}
                         .dump(1)
                  << "\n";
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
