#include "render/kinds/silhouette_shell_pass.h"

#include "core/gpu/check.h"
#include "core/gpu/context.h"
#include "shaders/embedded.h"
#include "shaders/shared/effect_draw.h"
#include "sim/scene_simulation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace mfx::render {

namespace {

gpu::Program computeProgram(const gpu::Context& ctx, const char* name,
                            std::span<const uint32_t> spirv) {
    return storageComputeProgram(ctx, name, spirv, sizeof(shared::SilhouetteShellConstants));
}

void computeToTransfer(VkCommandBuffer cmd) {
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                       VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                       VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

} // namespace

std::vector<uint32_t> shellVertexTriangles(const std::vector<shared::SkinVertexIn>& vertices,
                                           const std::vector<uint32_t>& triangles) {
    // Weld by exact bind-pose position: the copies of a seam vertex are made from one point.
    const Welding welding = weldByPosition(vertices);
    const std::vector<uint32_t>& weldedIndex = welding.group;
    std::vector<std::vector<uint32_t>> around(welding.groupCount);
    for (size_t t = 0; t + 2 < triangles.size(); t += 3)
        for (size_t k = 0; k < 3; ++k) {
            std::vector<uint32_t>& list = around[weldedIndex[triangles[t + k]]];
            // A degenerate polygon with two corners at one point counts once.
            if (list.empty() || list.back() != uint32_t(t / 3)) list.push_back(uint32_t(t / 3));
        }
    std::vector<uint32_t> out(vertices.size() + 1);
    uint32_t at = uint32_t(vertices.size() + 1);
    for (size_t v = 0; v < vertices.size(); ++v) {
        out[v] = at;
        at += uint32_t(around[weldedIndex[v]].size());
    }
    out[vertices.size()] = at;
    for (size_t v = 0; v < vertices.size(); ++v) {
        const std::vector<uint32_t>& list = around[weldedIndex[v]];
        out.insert(out.end(), list.begin(), list.end());
    }
    return out;
}

ShellCadence shellCadence(const scene::SilhouetteShellSpec& shell, float fps) {
    ShellCadence cadence;
    if (!shell.blurTime || *shell.blurTime <= 0.0f || fps <= 0.0f) return cadence;
    const double perFrame = double(shell.subdivisions) / (double(*shell.blurTime) * double(fps));
    if (perFrame >= 1.0) {
        cadence.updatesPerFrame = uint32_t(
            std::clamp<double>(std::round(perFrame), 1.0, double(MFX_SHELL_MAX_UPDATES_PER_FRAME)));
    } else {
        // The scene file bounds blur_time (60 s) and subdivisions (>= 1); the bound here only keeps
        // the count finite for any caller.
        cadence.framesPerUpdate =
            uint32_t(std::clamp<double>(std::round(1.0 / perFrame), 1.0, 1e6));
    }
    return cadence;
}

SilhouetteShellPass::SilhouetteShellPass(const gpu::Context& ctx, const scene::Scene& scene,
                                         std::span<const anim::Character> cast,
                                         VkSampleCountFlagBits samples)
    : MeshEffectPass(ctx, cast) {
    for (Selected& selected : selectedEffects(scene)) {
        const Kind* kind = selected.kind;
        // A triangle with two corners at one point has no edge to sweep: its strip would be a
        // line. Leaving such triangles out keeps every strip a surface.
        std::vector<uint32_t> kept;
        const std::vector<uint32_t>& all = selected.source.triangles;
        for (size_t t = 0; t + 2 < all.size(); t += 3) {
            const glm::vec3 p0(selected.source.vertices[all[t]].position);
            const glm::vec3 p1(selected.source.vertices[all[t + 1]].position);
            const glm::vec3 p2(selected.source.vertices[all[t + 2]].position);
            if (p0 == p1 || p1 == p2 || p2 == p0) continue;
            kept.insert(kept.end(), all.begin() + ptrdiff_t(t), all.begin() + ptrdiff_t(t + 3));
        }
        if (kept.empty()) continue;
        selected.source.triangles = std::move(kept);
        Effect effect(MeshEffect(ctx, selected.index, meshEffectColour(*kind),
                                 std::move(selected.source), 0, "shell"),
                      *kind);
        const trajectory::Source& source = effect.source;
        const uint32_t n = effect.vertexCount;
        effect.triangleCount = uint32_t(source.triangles.size() / 3);
        // Sec. 3.2.3: one ring slot a subdivision, and one for the latest update (the live mesh).
        effect.historySlots = kind->subdivisions + 1;
        effect.cadence = shellCadence(*kind, scene.output.fps);
        const std::vector<uint32_t> adjacency =
            shellVertexTriangles(source.vertices, source.triangles);
        // Every polygon drawing a full strip: the most one frame can build (Sec. 3.2.5).
        const VkDeviceSize outputCapacity =
            VkDeviceSize(effect.triangleCount) * 6 * kind->subdivisions;

        effect.adjacency =
            effectStorage(ctx, adjacency.size() * sizeof(uint32_t), 0, "shell adjacency");
        gpu::uploadBuffer(ctx, effect.adjacency, std::span<const uint32_t>(adjacency));
        effect.triangles =
            effectStorage(ctx, source.triangles.size() * sizeof(uint32_t), 0, "shell triangles");
        gpu::uploadBuffer(ctx, effect.triangles, std::span<const uint32_t>(source.triangles));
        effect.current = effectStorage(ctx, n * sizeof(shared::ShellVertex), 0, "shell current");
        effect.last = effectStorage(ctx, n * sizeof(shared::ShellVertex), 0, "shell last frame");
        effect.states = effectStorage(
            ctx, VkDeviceSize(effect.triangleCount) * sizeof(shared::ShellTriangleState), 0,
            "shell states");
        effect.history = effectStorage(ctx,
                                       VkDeviceSize(effect.triangleCount) * effect.historySlots *
                                           sizeof(shared::ShellHistoryEdge),
                                       0, "shell history");
        effect.output = effectStorage(ctx, outputCapacity * sizeof(shared::TrajectoryVertex),
                                      VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "shell geometry");
        effect.counters =
            effectCounters(ctx, sizeof(shared::SilhouetteShellCounters), "shell counters");
        effect.resources = gpu::bindBuffers(
            {effect.skinned, effect.adjacency, effect.triangles, effect.current, effect.last,
             effect.states, effect.history, effect.colours, effect.output, effect.counters});
        effect.style = volumeStyleBuffer(ctx, kind->look);
        effects_.push_back(std::move(effect));
    }
    if (effects_.empty()) return; // a scene without the effect pays for nothing

    normals_ =
        computeProgram(ctx, "silhouette_shell_normals", shaders::silhouette_shell_normals_comp);
    update_ = computeProgram(ctx, "silhouette_shell_update", shaders::silhouette_shell_update_comp);
    build_ = computeProgram(ctx, "silhouette_shell_build", shaders::silhouette_shell_build_comp);

    // Translucent and unsorted, like the swept volume: the strips do not write depth.
    draw_ =
        trajectoryDrawProgram(ctx, "silhouette_shell", TrajectoryShape::Triangles, samples, false);
    frame_ = sceneFrameBuffer(ctx, "shell frame");
}

void SilhouetteShellPass::recordEffect(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                                       uint32_t frame, Effect& effect, bool reset) {
    const float time = simulation.frameTime(frame);
    shared::SilhouetteShellCounters zero{};
    zero.instanceCount = 1;
    vkCmdUpdateBuffer(cmd, effect.counters.get(), 0, sizeof zero, &zero);
    if (reset) {
        // A new start (first frame, a jump, a new simulation): no polygon has an edge yet and
        // every slot is empty.
        vkCmdFillBuffer(cmd, effect.states.get(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, effect.history.get(), 0, VK_WHOLE_SIZE, 0);
        effect.newest = 0;
    }
    transferToComputeBarrier(cmd);

    const scene::SilhouetteShellSpec& e = effect.kind;
    shared::SilhouetteShellConstants c{};
    c.vertexCount = effect.vertexCount;
    c.triangleCount = effect.triangleCount;
    c.historySlots = effect.historySlots;
    c.subdivisions = e.subdivisions;
    c.newest = effect.newest;
    c.updatesPerFrame = effect.cadence.updatesPerFrame;
    c.edgeRule =
        e.edgeRule == scene::ShellEdgeRule::Back ? MFX_SHELL_EDGE_BACK : MFX_SHELL_EDGE_FRONT;
    c.initialAlpha = e.initialAlpha;
    c.fadeOut = e.fadeOut;

    normals_.bind(cmd, effect.resources);
    normals_.push(cmd, c);
    vkCmdDispatch(cmd, gpu::groupCount(effect.vertexCount, MFX_SHELL_GROUP_SIZE), 1, 1);
    computeToComputeBarrier(cmd);
    // The first frame after a start only sets where the vertices were: a motion needs two.
    // With a blur time longer than subdivisions frames, frames between two updates only build
    // (from the live mesh back through the ring) and the motion of the next update runs from
    // the vertices of the last one.
    effect.framesSinceUpdate = reset ? 0 : effect.framesSinceUpdate + 1;
    effect.updated = !reset && effect.framesSinceUpdate >= effect.cadence.framesPerUpdate;
    if (effect.updated) {
        for (uint32_t u = 0; u < effect.cadence.updatesPerFrame; ++u) {
            effect.newest = (effect.newest + 1) % effect.historySlots;
            c.newest = effect.newest;
            c.update = u;
            update_.bind(cmd, effect.resources);
            update_.push(cmd, c);
            vkCmdDispatch(cmd, gpu::groupCount(effect.triangleCount, MFX_SHELL_GROUP_SIZE), 1, 1);
            computeToComputeBarrier(cmd);
        }
        effect.framesSinceUpdate = 0;
    }
    if (reset || effect.updated) {
        // These vertices are where the next update's motion starts from.
        computeToTransfer(cmd);
        const VkBufferCopy copy{0, 0,
                                VkDeviceSize(effect.vertexCount) * sizeof(shared::ShellVertex)};
        vkCmdCopyBuffer(cmd, effect.current.get(), effect.last.get(), 1, &copy);
        transferToComputeBarrier(cmd);
    }

    // Outside its window the effect keeps updating its rings (so it enters the window with
    // the right history) but builds nothing.
    const bool live = simulation.effectLive(simulation.scene().effects[effect.index], time);
    if (!live) return;
    build_.bind(cmd, effect.resources);
    build_.push(cmd, c);
    vkCmdDispatch(cmd, gpu::groupCount(effect.triangleCount, MFX_SHELL_GROUP_SIZE), 1, 1);
}

SilhouetteShellPass::Counts SilhouetteShellPass::counts(size_t effect) const {
    const Effect* e = find(effect);
    if (!e) return {};
    const auto c = builtCounters<shared::SilhouetteShellCounters>(effect);
    Counts out;
    out.vertices = c.vertexCount;
    out.silhouetteTriangles = c.silhouetteTriangles;
    out.strips = c.strips;
    out.fadingStrips = c.fadingStrips;
    out.updatesPerFrame = e->cadence.updatesPerFrame;
    out.framesPerUpdate = e->cadence.framesPerUpdate;
    out.updated = e->updated;
    return out;
}

std::vector<shared::TrajectoryVertex> SilhouetteShellPass::geometry(size_t effect) const {
    return builtVertices(effect, counts(effect).vertices);
}

std::vector<glm::vec3> SilhouetteShellPass::livePositions(size_t effect) const {
    const Effect* e = find(effect);
    if (!e) return {};
    auto skinned = gpu::readBufferAs<shared::SkinVertexOut>(ctx_, e->skinned);
    std::vector<glm::vec3> out;
    for (size_t v = 0; v < std::min<size_t>(skinned.size(), e->vertexCount); ++v)
        out.push_back(glm::vec3(skinned[v].position));
    return out;
}

} // namespace mfx::render
