// motionfx render: a scene (or the built-in default) rendered headless, frame by frame, into
// numbered PNGs and, when ffmpeg is installed, an H.264 MP4, with a progress bar and per-frame
// stats.
#include "apps/commands.h"
#include "apps/progress.h"

#include "core/gpu/commands.h"
#include "render/effects_layer.h"
#include "render/image_output.h"
#include "render/scene_player.h"
#include "sim/scene_simulation.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <vector>

extern char** environ;

namespace mfx::app {

namespace {

// Runs the program argv[0] (looked up on PATH) with `argv`, no shell between, and waits: its exit
// status; -1 if it did not start (`missing` set when there is no such program) or did not exit.
int runProgram(const std::vector<std::string>& argv, bool& missing) {
    std::vector<char*> words;
    for (const std::string& word : argv)
        words.push_back(const_cast<char*>(word.c_str()));
    words.push_back(nullptr);
    pid_t pid = 0;
    const int started = posix_spawnp(&pid, words[0], nullptr, nullptr, words.data(), environ);
    missing = started == ENOENT;
    if (started != 0) return -1;
    int status = 0;
    if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
    return WEXITSTATUS(status);
}

// DIR/frame_0000.png ... as DIR/scene.mp4 with ffmpeg: H.264 in yuv420p, which browsers play, the
// picture padded by one black row or column to an even size where it is odd (4:2:0 halves both),
// exactly `frames` frames (higher-numbered frames left in DIR by an earlier run are not read) at
// `fps`. Returns the note for the closing line.
std::string encodeVideo(const std::string& dir, float fps, uint32_t frames) {
    char rate[32];
    std::snprintf(rate, sizeof rate, "%g", double(fps));
    bool missing = false;
    const int status = runProgram({"ffmpeg",
                                   "-nostdin",
                                   "-y",
                                   "-loglevel",
                                   "error",
                                   "-framerate",
                                   rate,
                                   "-i",
                                   dir + "/frame_%04d.png",
                                   "-frames:v",
                                   std::to_string(frames),
                                   "-vf",
                                   "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                   "-c:v",
                                   "libx264",
                                   "-pix_fmt",
                                   "yuv420p",
                                   "-movflags",
                                   "+faststart",
                                   dir + "/scene.mp4"},
                                  missing);
    if (missing) return " (ffmpeg is not installed: no MP4)";
    return status == 0 ? ", and " + dir + "/scene.mp4" : " (ffmpeg failed: no MP4)";
}

std::string frameName(uint32_t frame, const char* prefix = "frame") {
    char name[64];
    std::snprintf(name, sizeof name, "%s_%04u.png", prefix, frame);
    return name;
}

// The frame just played drawn again without its effects, and the effects alone as a layer
// (render/effects_layer.h): DIR/character_NNNN.png and DIR/effects_NNNN.png.
Status writeLayers(const gpu::Context& ctx, render::ScenePlayer& player, uint32_t frame,
                   const std::vector<uint8_t>& full, const std::string& dir) {
    render::FrameRenderer& renderer = player.renderer();
    sim::SceneSimulation& sim = player.simulation();
    const size_t effects = sim.scene().effects.size();
    for (size_t e = 0; e < effects; ++e)
        renderer.setShown(e, false);
    gpu::submitOneShot(
        ctx, [&](VkCommandBuffer cmd) { player.recordRedraw(cmd, sim.frameTime(frame)); });
    const std::vector<uint8_t> under = render::readColor(ctx, renderer.output());
    for (size_t e = 0; e < effects; ++e)
        renderer.setShown(e, true);
    const uint32_t w = renderer.output().width, h = renderer.output().height;
    if (Status s = render::writePng(dir + "/" + frameName(frame, "character"), w, h, under); !s)
        return s;
    return render::writePng(dir + "/" + frameName(frame, "effects"), w, h,
                            render::effectsLayer(full, under));
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
    VdbOutput vdb;
    if (!readVdbOutput(parsed, vdb)) return kExitFailure;
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
        reportBudget(stats);
        const std::vector<uint8_t> rgba = render::readColor(ctx, renderer.output());
        if (Status written = render::writePng(outDir + "/" + frameName(f), s.output.width,
                                              s.output.height, rgba);
            !written) {
            printError(written.error().message);
            return kExitFailure;
        }
        nlohmann::json record = statsJson(stats);
        record["effect_draws"] = renderer.effectDraws();
        frames.push_back(record);
        if (Status written = writeFrameVdbs(sim, f, vdb); !written) {
            printError(written.error().message);
            return kExitFailure;
        }
        if (parsed.has("layers"))
            if (Status layers = writeLayers(ctx, player, f, rgba, outDir); !layers) {
                printError(layers.error().message);
                return kExitFailure;
            }
        double gpu = 0.0;
        for (const sim::PassRecord& p : stats.passes)
            gpu += p.gpuMs;
        char note[64];
        std::snprintf(note, sizeof note, "(%.1f ms GPU)", gpu);
        progress.update(f + 1, note);
    }
    progress.finish();
    const std::string video = encodeVideo(outDir, s.output.fps, sim.frameCount());
    std::printf("rendered %s on %s: %u frames of %ux%u in %s/frame_0000.png ... %s%s\n",
                s.file.c_str(), ctx.info().name.c_str(), sim.frameCount(), s.output.width,
                s.output.height, outDir.c_str(), frameName(sim.frameCount() - 1).c_str(),
                video.c_str());
    if (vdb.on) std::printf("wrote %u OpenVDB files into %s\n", vdb.files, vdb.dir.c_str());
    reportMotionlessEffects(sim.scene(), argument.cast, sim.frameCount());
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
