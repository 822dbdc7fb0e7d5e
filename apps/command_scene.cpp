// motionfx scene: what a scene file asks for (character, clip, frames, and each effect with the
// vertices its bones and meshes select), or the one-line reason it is refused.
#include "apps/commands.h"

#include "core/scene/effect_source.h"
#include "core/scene/scene.h"
#include "core/trajectory/surface_source.h"
#include "core/trajectory/trajectory_source.h"

#include <cstdio>

namespace mfx::app {

int runScene(const cli::ParsedArgs& parsed) {
    SceneArgument argument;
    int exitCode = kExitOk;
    if (!loadSceneArgument(parsed, argument, exitCode)) return exitCode;
    const scene::Scene& s = argument.scene;
    const anim::Character& c = argument.character;
    const anim::Clip& clip = scene::sceneClip(s, c);
    std::printf("scene        %s\n", s.file.c_str());
    std::printf("character    %s, clip %s (%.3g s), from %.3g s at speed %.3g%s\n",
                s.character.source.c_str(), clip.name.c_str(), double(clip.duration),
                double(s.character.start), double(s.character.speed),
                s.character.loop ? ", looping" : "");
    std::printf("output       %ux%u, %.3g fps, %u frames (%.3g s)\n", s.output.width,
                s.output.height, double(s.output.fps), scene::frameCount(s, c),
                double(scene::frameCount(s, c)) / double(s.output.fps));
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
        const Result<trajectory::Source> source = scene::effectSource(c, e, &report);
        std::string window = "from " + std::to_string(e.start).substr(0, 5) + " s";
        if (e.end) window += " to " + std::to_string(*e.end).substr(0, 5) + " s";
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
    return kExitOk;
}

} // namespace mfx::app
