// motionfx bench effects: what each motion-effect technique adds to a frame, measured the way the
// afterimage thesis (Smith 2016) tabulates its techniques: the extra GPU milliseconds per frame and
// the extra triangles per frame against the character alone on the same clip, and the share of the
// frame's time the effect takes. Each technique runs in its demo scene (docs/scenes/<name>.json,
// one effect each); the baseline is the same scene with its effects removed. Triangles are the
// primitives that reach the clipper (a pipeline-statistics query around the whole frame), so every
// pass counts: shadow, scene, effects and the smoke's proxy and composite.
#include "apps/commands.h"
#include "apps/progress.h"

#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "render/scene_player.h"
#include "sim/scene_simulation.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace mfx::app {

namespace {

// The demo scene of every technique, relative to the project root.
constexpr const char* kDefaultScenes[] = {"docs/scenes/lines.json",      "docs/scenes/blur.json",
                                          "docs/scenes/particles.json",  "docs/scenes/smoke.json",
                                          "docs/scenes/afterimage.json", "docs/scenes/swept.json",
                                          "docs/scenes/shell.json"};

struct Measure {
    double gpuMs = 0.0;     // median GPU ms per timed frame (simulation and drawing)
    double triangles = 0.0; // mean primitives reaching the clipper per timed frame
    uint32_t frames = 0;    // timed
};

// Runs `argument`'s scene through, timing every frame after the first `skip`.
bool measure(const gpu::Context& ctx, const SceneArgument& argument, VkSampleCountFlagBits samples,
             uint32_t skip, const gpu::PrimitiveCounter& primitives, Measure& out, int& exitCode) {
    const std::unique_ptr<sim::SceneSimulation> sim =
        createSceneSimulation(ctx, argument, exitCode);
    if (!sim) return false;
    const scene::Scene& s = argument.scene;
    render::ScenePlayer player(ctx, *sim, s.output.width, s.output.height, samples);
    std::vector<double> gpuMs;
    double triangles = 0.0;
    for (uint32_t f = 0; f < sim->frameCount(); ++f) {
        const sim::SimulationFrameStats stats = player.play(f, &primitives);
        if (f < skip) continue; // pipeline compiles run inside the first frames on a CPU driver
        double ms = 0.0;
        for (const sim::PassRecord& p : stats.passes) // the drawing's passes among them
            ms += p.gpuMs;
        gpuMs.push_back(ms);
        triangles += double(primitives.result());
    }
    out.frames = uint32_t(gpuMs.size());
    out.gpuMs = gpuMs.empty() ? 0.0 : median(gpuMs);
    out.triangles = gpuMs.empty() ? 0.0 : triangles / double(gpuMs.size());
    return true;
}

} // namespace

int runBenchEffects(const cli::ParsedArgs& parsed) {
    int exitCode = kExitOk;
    const Result<uint32_t> samples = parseSamples(parsed);
    auto skip = cli::parseUnsigned(parsed.value("skip", "2"), 0, 1000, "--skip");
    if (reportFirstError(samples, skip)) return kExitUsage;
    std::vector<std::string> files = parsed.positional;
    if (files.empty())
        for (const char* f : kDefaultScenes)
            if (std::filesystem::exists(f)) files.push_back(f);
    if (files.empty()) {
        printError("no scene files: run from the project root (for docs/scenes/) or name the "
                   "scenes");
        return kExitUsage;
    }
    std::ofstream jsonFile;
    if (!openOutputFile(parsed.value("json"), jsonFile)) return kExitFailure;

    // Every scene loads before the GPU starts: a bad file fails at once.
    std::vector<SceneArgument> withEffects(files.size());
    for (size_t i = 0; i < files.size(); ++i) {
        cli::ParsedArgs one = parsed;
        one.positional = {files[i]};
        if (!loadSceneArgument(one, withEffects[i], exitCode, "960x540")) return exitCode;
        if (withEffects[i].scene.effects.empty()) {
            printError(files[i] + ": the scene has no effect to measure");
            return kExitUsage;
        }
    }

    const std::unique_ptr<gpu::Context> context = createTimingContext(parsed, "the frames");
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    const gpu::PrimitiveCounter primitives(ctx);
    if (!primitives.valid()) {
        printError(ctx.info().name + " has no pipeline-statistics queries; triangles cannot be "
                                     "counted");
        return kExitFailure;
    }
    for (const SceneArgument& a : withEffects)
        if (!checkOutputSize(ctx, a.scene)) return kExitFailure;

    struct Row {
        std::string effect, file;
        Measure alone, with;
    };
    std::vector<Row> rows;
    Progress progress("scenes", uint32_t(2 * files.size()));
    for (size_t i = 0; i < files.size(); ++i) {
        SceneArgument& with = withEffects[i];
        std::string effect = with.scene.effects.front().type();
        for (size_t e = 1; e < with.scene.effects.size(); ++e)
            effect += std::string("+") + with.scene.effects[e].type();
        SceneArgument alone{with.scene, with.cast};
        // The characters alone keep the scene's hit-stops (its hits stay, their impacts gone:
        // scene::hitImpact), so both runs play the same motion.
        alone.scene.effects.clear();
        Row row{effect, files[i]};
        const VkSampleCountFlagBits wanted = VkSampleCountFlagBits(samples.value());
        if (!measure(ctx, alone, wanted, skip.value(), primitives, row.alone, exitCode))
            return exitCode;
        progress.update(uint32_t(2 * i + 1));
        if (!measure(ctx, with, wanted, skip.value(), primitives, row.with, exitCode))
            return exitCode;
        progress.update(uint32_t(2 * i + 2));
        rows.push_back(row);
    }
    progress.finish();

    const scene::Scene& first = withEffects.front().scene;
    std::printf(
        "effects benchmark on %s (%s), %ux%u, up to %u samples per pixel; GPU ms: median "
        "per frame after %u untimed frames; triangles: mean primitives clipped per frame\n\n",
        ctx.info().name.c_str(), ctx.info().driverInfo.c_str(), first.output.width,
        first.output.height, samples.value(), skip.value());
    std::printf("%-18s %-28s %6s %10s %10s %9s %8s %12s %12s\n", "effect", "scene", "frames",
                "alone ms", "with ms", "extra ms", "share", "alone tris", "extra tris");
    nlohmann::json effects = nlohmann::json::object();
    for (const Row& r : rows) {
        const double extraMs = r.with.gpuMs - r.alone.gpuMs;
        const double extraTris = r.with.triangles - r.alone.triangles;
        const double share = r.with.gpuMs > 0.0 ? 100.0 * extraMs / r.with.gpuMs : 0.0;
        std::printf("%-18s %-28s %6u %10.2f %10.2f %9.2f %7.1f%% %12.0f %12.0f\n", r.effect.c_str(),
                    r.file.c_str(), r.with.frames, r.alone.gpuMs, r.with.gpuMs, extraMs, share,
                    r.alone.triangles, extraTris);
        effects[r.effect] = {{"scene", r.file},
                             {"frames", r.with.frames},
                             {"alone_ms", r.alone.gpuMs},
                             {"with_ms", r.with.gpuMs},
                             {"extra_ms", extraMs},
                             {"frame_share_percent", share},
                             {"alone_triangles", r.alone.triangles},
                             {"extra_triangles", extraTris}};
    }
    if (jsonFile.is_open())
        jsonFile << nlohmann::json{{"device", ctx.info().name},
                                   {"driver", ctx.info().driverInfo},
                                   {"size", {first.output.width, first.output.height}},
                                   {"samples", samples.value()},
                                   {"effects", effects}}
                        .dump(2)
                 << "\n";
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
