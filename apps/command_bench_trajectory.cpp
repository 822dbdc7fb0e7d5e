// motionfx bench trajectory: the split trajectory method against the unsplit baseline on the
// built-in fighter's roundhouse kick, for a range of lifetimes L: skinning evaluations, trajectory
// vertices and GPU milliseconds per frame (Xu et al., section 5, Fig. 12-14). Prints a table,
// draws the plot as SVG, and writes JSON and per-frame statistics on request.
#include "apps/commands.h"
#include "apps/svg_plot.h"

#include "core/anim/fighter.h"
#include "core/gpu/commands.h"
#include "core/trajectory/trajectory_queue.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace mfx::app {

namespace {

Result<std::vector<uint32_t>> parseLifetimes(const std::string& text) {
    std::vector<uint32_t> out;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        auto value = cli::parseUnsigned(item, 1, 1024, "--lifetimes");
        if (!value) return value.error();
        out.push_back(value.value());
    }
    if (out.empty()) return Error{"--lifetimes needs at least one lifetime, e.g. 1,2,4,8"};
    return out;
}

struct Row {
    trajectory::Method method;
    uint32_t lifetime = 0;
    trajectory::FrameStats stats; // of the last timed frame (the trail full)
    double gpuMs = 0.0;           // median over the timed frames
    double wallMs = 0.0;          // median record + submit + wait
    uint64_t gsVertices = 0;      // what one geometry-shader invocation would have to emit
};

} // namespace

int runBenchTrajectory(const cli::ParsedArgs& parsed) {
    auto lifetimes = parseLifetimes(parsed.value("lifetimes", "1,2,4,8,16,32,64"));
    auto subSamples = cli::parseUnsigned(parsed.value("sub-samples", "4"), 1,
                                         MFX_TRAJECTORY_MAX_SUBSAMPLES, "--sub-samples");
    auto frames = cli::parseUnsigned(parsed.value("frames", "20"), 1, 100000, "--frames");
    if (reportFirstError(lifetimes, subSamples, frames)) return kExitUsage;
    const anim::Character fighter = anim::makeFighter();
    const std::string clipName = parsed.value("clip", "roundhouse_kick");
    const anim::Clip* clip = fighter.findClip(clipName);
    if (!clip) {
        std::string names;
        for (const anim::Clip& c : fighter.clips)
            names += (names.empty() ? "" : ", ") + c.name;
        printError("--clip: the fighter has no clip \"" + clipName + "\"; clips are: " + names);
        return kExitUsage;
    }
    const std::string plotPath = parsed.value("plot", "out/bench_trajectory.svg");
    std::ofstream jsonFile, statsFile;
    if (!openOutputFile(parsed.value("json"), jsonFile)) return kExitFailure;
    if (!openOutputFile(parsed.value("stats"), statsFile)) return kExitFailure;

    const std::unique_ptr<gpu::Context> context =
        createTimingContext(parsed, "the trajectory pass");
    if (!context) return kExitFailure;
    const gpu::Context& ctx = *context;
    const trajectory::Source source = trajectory::selectSource(fighter, {}).value();
    const uint32_t maxLifetime =
        *std::max_element(lifetimes.value().begin(), lifetimes.value().end());
    // The most vertices one geometry-shader invocation may emit with a 16-float vertex (the
    // stream-output route of the paper), or 0 when the device has no geometry shaders.
    const VkPhysicalDeviceLimits& limits = ctx.limits();
    const uint64_t gsLimit = ctx.features().geometryShader
                                 ? std::min<uint64_t>(limits.maxGeometryOutputVertices,
                                                      limits.maxGeometryTotalOutputComponents / 16)
                                 : 0;
    std::printf("trajectory benchmark on %s (%s)\nthe fighter's %s, all %zu vertices, motion "
                "lines, S = %u; median of %u frames at 60 fps after the trail has filled; GPU "
                "milliseconds from timestamp queries\n\n",
                ctx.info().name.c_str(), ctx.info().driverInfo.c_str(), clipName.c_str(),
                source.vertices.size(), subSamples.value(), frames.value());

    std::vector<trajectory::Method> methods = {trajectory::Method::Split};
    {
        // The geometry-shader route only where the device (and the loader as set up) offers it.
        trajectory::QueueOptions probe;
        probe.method = trajectory::Method::StreamOutput;
        probe.lifetime = probe.maxLifetime = 1;
        const auto xfb = trajectory::Queue::create(ctx, source, probe);
        if (xfb)
            methods.push_back(trajectory::Method::StreamOutput);
        else
            std::printf("(no split-xfb rows: %s)\n\n", xfb.error().message.c_str());
    }
    methods.push_back(trajectory::Method::Unsplit);
    std::vector<Row> rows;
    nlohmann::json frameLog = nlohmann::json::array();
    for (trajectory::Method method : methods)
        for (uint32_t lifetime : lifetimes.value()) {
            trajectory::QueueOptions queueOptions;
            queueOptions.kind = trajectory::Kind::Lines;
            queueOptions.method = method;
            queueOptions.segment.subSamples = subSamples.value();
            queueOptions.lifetime = lifetime;
            queueOptions.maxLifetime = maxLifetime;
            auto created = trajectory::Queue::create(ctx, source, queueOptions);
            if (!created) {
                printError(created.error().message);
                return kExitFailure;
            }
            trajectory::Queue& queue = *created.value();
            std::fprintf(stderr, "  %-7s L=%-4u ", trajectory::methodName(method), lifetime);
            std::vector<double> gpu, wall;
            const uint32_t warmup = lifetime + 5; // the trail full, the pipeline compiled
            for (uint32_t f = 0; f < warmup + frames.value(); ++f) {
                const float t = float(f) / 60.0f;
                const auto palette = trajectory::sourcePalette(
                    fighter, source, anim::samplePose(fighter, clip, t, anim::Wrap::Loop));
                const auto start = std::chrono::steady_clock::now();
                gpu::submitOneShot(ctx,
                                   [&](VkCommandBuffer cmd) { queue.record(cmd, palette, t); });
                const double ms = std::chrono::duration<double, std::milli>(
                                      std::chrono::steady_clock::now() - start)
                                      .count();
                if (f % 8 == 0) std::fputc('.', stderr);
                if (f < warmup) continue;
                gpu.push_back(queue.lastGpuMilliseconds());
                wall.push_back(ms);
                const trajectory::FrameStats& s = queue.lastFrame();
                frameLog.push_back({{"method", trajectory::methodName(method)},
                                    {"lifetime", lifetime},
                                    {"frame", f},
                                    {"time", t},
                                    {"skinning_evaluations", s.skinningEvaluations},
                                    {"vertices_generated", s.verticesGenerated},
                                    {"bytes_written", s.bytesWritten},
                                    {"live_segments", s.liveSegments},
                                    {"gpu_ms", gpu.back()}});
            }
            std::fputc('\n', stderr);
            Row row;
            row.method = method;
            row.lifetime = lifetime;
            row.stats = queue.lastFrame();
            row.gpuMs = median(gpu);
            row.wallMs = median(wall);
            row.gsVertices = uint64_t(subSamples.value() + 1) *
                             (method == trajectory::Method::Unsplit ? lifetime : 1);
            rows.push_back(row);
        }

    std::printf("%-8s %5s %14s %14s %12s %10s %10s %14s\n", "method", "L", "skinning/frame",
                "vertices/frame", "MB/frame", "GPU ms", "wall ms", "GS vertices");
    for (const Row& r : rows) {
        std::string gs = std::to_string(r.gsVertices);
        if (gsLimit > 0 && r.gsVertices > gsLimit) gs += " > limit";
        std::printf("%-8s %5u %14llu %14llu %12.2f %10.3f %10.3f %14s\n",
                    trajectory::methodName(r.method), r.lifetime,
                    static_cast<unsigned long long>(r.stats.skinningEvaluations),
                    static_cast<unsigned long long>(r.stats.verticesGenerated),
                    double(r.stats.bytesWritten) / 1e6, r.gpuMs, r.wallMs, gs.c_str());
    }
    std::printf("\nGS vertices: what one geometry-shader invocation would emit per source vertex "
                "to build the same trail with stream output; ");
    if (gsLimit > 0)
        std::printf("this device allows %llu (maxGeometryOutputVertices %u, "
                    "maxGeometryTotalOutputComponents %u / 16 floats).\n",
                    static_cast<unsigned long long>(gsLimit), limits.maxGeometryOutputVertices,
                    limits.maxGeometryTotalOutputComponents);
    else
        std::printf("this device has no geometry shaders.\n");
    for (const uint32_t l : lifetimes.value()) {
        const Row* by[3] = {nullptr, nullptr, nullptr};
        for (const Row& r : rows)
            if (r.lifetime == l) by[int(r.method)] = &r;
        const Row* split = by[int(trajectory::Method::Split)];
        if (!split || split->gpuMs <= 0) continue;
        std::printf("L=%-4u GPU time relative to split:", l);
        for (trajectory::Method m : {trajectory::Method::StreamOutput, trajectory::Method::Unsplit})
            if (by[int(m)])
                std::printf("  %s %.2fx", trajectory::methodName(m),
                            by[int(m)]->gpuMs / split->gpuMs);
        std::printf("\n");
    }

    // The plot: GPU ms and skinning evaluations per frame against L, both methods.
    std::vector<PlotPanel> panels(2);
    panels[0] = {"GPU time per frame", "lifetime L (frames)", "GPU ms per frame", true, true, {}};
    panels[1] = {
        "skinning evaluations per frame", "lifetime L (frames)", "evaluations", true, true, {}};
    for (trajectory::Method method : {trajectory::Method::Split, trajectory::Method::Unsplit}) {
        PlotSeries ms{trajectory::methodName(method),
                      method == trajectory::Method::Split ? "#1f77b4" : "#d62728",
                      {},
                      {}};
        PlotSeries skins = ms;
        for (const Row& r : rows)
            if (r.method == method) {
                ms.x.push_back(r.lifetime);
                ms.y.push_back(r.gpuMs);
                skins.x.push_back(r.lifetime);
                skins.y.push_back(double(r.stats.skinningEvaluations));
            }
        panels[0].series.push_back(ms);
        panels[1].series.push_back(skins);
    }
    std::error_code ec;
    const std::filesystem::path plot(plotPath);
    if (plot.has_parent_path()) std::filesystem::create_directories(plot.parent_path(), ec);
    std::ofstream plotFile(plot);
    if (!plotFile) {
        printError("cannot write " + plotPath);
        return kExitFailure;
    }
    plotFile << svgPlot("Split trajectory vs unsplit baseline: " + ctx.info().name + ", " +
                            std::to_string(source.vertices.size()) +
                            " vertices, S = " + std::to_string(subSamples.value()),
                        panels);
    std::printf("plot: %s\n", plotPath.c_str());

    if (jsonFile.is_open()) {
        nlohmann::json list = nlohmann::json::array();
        for (const Row& r : rows)
            list.push_back({{"method", trajectory::methodName(r.method)},
                            {"lifetime", r.lifetime},
                            {"skinning_per_frame", r.stats.skinningEvaluations},
                            {"vertices_per_frame", r.stats.verticesGenerated},
                            {"bytes_per_frame", r.stats.bytesWritten},
                            {"gpu_ms", r.gpuMs},
                            {"wall_ms", r.wallMs},
                            {"gs_vertices_per_invocation", r.gsVertices},
                            {"gs_vertex_limit", gsLimit}});
        jsonFile << nlohmann::json{{"device", ctx.info().name},
                                   {"driver", ctx.info().driverInfo},
                                   {"clip", clipName},
                                   {"source_vertices", source.vertices.size()},
                                   {"sub_samples", subSamples.value()},
                                   {"frames", frames.value()},
                                   {"rows", list}}
                        .dump(2)
                 << "\n";
    }
    if (statsFile.is_open()) statsFile << frameLog.dump(1) << "\n";
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app
