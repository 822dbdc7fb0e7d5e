// motionfx scene: what a scene file asks for (its characters and clips, frames, and each effect
// with the vertices its bones and meshes select), or the one-line reason it is refused.
#include "apps/commands.h"

#include "core/scene/effect_source.h"
#include "core/scene/kinds/impact_effect.h"
#include "core/scene/scene.h"
#include "core/scene/scene_hits.h"
#include "core/trajectory/surface_source.h"
#include "core/trajectory/trajectory_source.h"

#include <algorithm>
#include <cstdio>

namespace mfx::app {

namespace {

// The impacts' hits: when, where, which bones, how fast, and the hit-stop.
void printHits(const scene::Scene& s) {
    const bool impacts =
        std::any_of(s.effects.begin(), s.effects.end(),
                    [](const scene::EffectSpec& e) { return e.is<scene::ImpactSpec>(); });
    if (!impacts) return;
    std::printf("hits         %zu\n", s.hits.size());
    for (const scene::Hit& h : s.hits) {
        if (!scene::hitImpact(s, h)) continue;
        char stop[32] = "";
        if (h.holdFrames > 0)
            std::snprintf(stop, sizeof stop, ", hit-stop %u frames", h.holdFrames);
        std::printf("  %-18s frame %u (%.4f s): %s.%s on %s.%s at (%.3f, %.3f, %.3f), "
                    "%.2f m/s along (%.2f, %.2f, %.2f)%s\n",
                    s.effects[h.effect].name.c_str(), h.frame, double(h.time),
                    s.characters[h.attacker].name.c_str(), h.attackerBone.c_str(),
                    s.characters[h.target].name.c_str(), h.targetBone.c_str(), double(h.point.x),
                    double(h.point.y), double(h.point.z), double(h.speed), double(h.direction.x),
                    double(h.direction.y), double(h.direction.z), stop);
    }
}

} // namespace

int runScene(const cli::ParsedArgs& parsed) {
    SceneArgument argument;
    int exitCode = kExitOk;
    if (!loadSceneArgument(parsed, argument, exitCode)) return exitCode;
    const scene::Scene& s = argument.scene;
    const scene::Cast& cast = argument.cast;
    std::printf("scene        %s\n", s.file.c_str());
    for (size_t i = 0; i < cast.size(); ++i) {
        const scene::CharacterSpec& spec = s.characters[i];
        const anim::Clip& clip = scene::sceneClip(spec, cast[i]);
        const std::string name = cast.size() == 1 ? std::string() : "\"" + spec.name + "\": ";
        char delay[48] = "";
        if (spec.delay > 0.0f)
            std::snprintf(delay, sizeof delay, " after a delay of %.3g s", double(spec.delay));
        std::printf("%-12s %s%s, clip %s (%.3g s), from %.3g s at speed %.3g%s%s\n",
                    i == 0 ? (cast.size() == 1 ? "character" : "characters") : "", name.c_str(),
                    spec.source.c_str(), clip.name.c_str(), double(clip.duration),
                    double(spec.start), double(spec.speed), delay, spec.loop ? ", looping" : "");
    }
    const uint32_t frames = scene::frameCount(s, cast);
    std::printf("output       %ux%u, %.3g fps, %u frames (%.3g s)\n", s.output.width,
                s.output.height, double(s.output.fps), frames,
                double(frames) / double(s.output.fps));
    std::printf("camera       at (%.3g, %.3g, %.3g) looking at (%.3g, %.3g, %.3g), %.3g degrees; "
                "floor at y = %.3g\n",
                double(s.camera.position.x), double(s.camera.position.y),
                double(s.camera.position.z), double(s.camera.target.x), double(s.camera.target.y),
                double(s.camera.target.z), double(s.camera.fovDegrees),
                double(s.stage.floorHeight));
    std::printf("effects      %zu\n", s.effects.size());
    for (const scene::EffectSpec& e : s.effects) {
        const std::optional<float> surfaceStep = e.kind().surfaceSampling();
        const bool surface = surfaceStep.has_value();
        trajectory::SurfaceReport report;
        const size_t follows = scene::effectCharacter(s, e);
        const Result<trajectory::Source> source = scene::effectSource(cast[follows], e, &report);
        std::string window = "from " + std::to_string(e.start).substr(0, 5) + " s";
        if (e.end) window += " to " + std::to_string(*e.end).substr(0, 5) + " s";
        if (cast.size() > 1) window = "on \"" + s.characters[follows].name + "\", " + window;
        std::printf("  %-18s %-16s %s, ", e.name.c_str(), e.type(), window.c_str());
        if (!source) {
            std::printf("%s\n", source.error().message.c_str());
            continue;
        }
        std::string bones = "the whole character";
        if (!e.bones.empty()) {
            bones.clear();
            for (const std::string& b : e.bones)
                bones += (bones.empty() ? "" : ", ") + b;
        }
        if (!surface) {
            std::printf("%zu vertices, %zu triangles selected", source.value().vertices.size(),
                        source.value().triangles.size() / 3);
            if (const scene::TrailSpec* trail = e.kind().queue())
                std::printf(", stride %u", trail->stride);
            std::printf("\n");
            std::printf("  %-18s bones: %s\n", "", bones.c_str());
            continue;
        }
        std::printf("%zu surface points from %zu triangles (step %.3g)", report.samples,
                    report.triangles, double(*surfaceStep));
        if (report.degenerateInUv + report.degenerateInModel + report.withoutUv > 0)
            std::printf("; skipped %zu degenerate in UV, %zu without area, %zu without UVs",
                        report.degenerateInUv, report.degenerateInModel, report.withoutUv);
        for (const std::string& mesh : report.overlappingMeshes)
            std::printf("; warning: mesh \"%s\" has overlapping UVs", mesh.c_str());
        std::printf("\n  %-18s bones: %s\n", "", bones.c_str());
    }
    printHits(s);
    return kExitOk;
}

} // namespace mfx::app
