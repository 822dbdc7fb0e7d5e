#include "render/kinds/swept_volume_pass.h"

#include "core/gpu/check.h"
#include "core/gpu/context.h"
#include "shaders/embedded.h"
#include "shaders/shared/effect_draw.h"
#include "sim/scene_simulation.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <utility>

namespace mfx::render {

namespace {

gpu::Program computeProgram(const gpu::Context& ctx, const char* name,
                            std::span<const uint32_t> spirv) {
    return storageComputeProgram(ctx, name, spirv, sizeof(shared::SweptVolumeConstants));
}

uint32_t filterCode(scene::SweptFilter filter) {
    switch (filter) {
    case scene::SweptFilter::Box:
        return MFX_SWEPT_BOX;
    case scene::SweptFilter::Ramp:
        return MFX_SWEPT_RAMP;
    case scene::SweptFilter::Triangle:
        return MFX_SWEPT_TRIANGLE;
    case scene::SweptFilter::Gaussian:
        return MFX_SWEPT_GAUSSIAN;
    }
    return MFX_SWEPT_RAMP;
}

} // namespace

std::vector<uint32_t> sweptVolumeEdges(const std::vector<shared::SkinVertexIn>& vertices,
                                       const std::vector<uint32_t>& triangles) {
    // Weld by exact bind-pose position: the copies of a seam vertex are made from one point.
    const Welding welding = weldByPosition(vertices);
    const std::vector<uint32_t>& weldedIndex = welding.group;
    struct Side {
        uint32_t triangle, a, b;
    };
    std::map<std::pair<uint32_t, uint32_t>, std::vector<Side>> sides;
    for (size_t t = 0; t + 2 < triangles.size(); t += 3)
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t a = triangles[t + k], b = triangles[t + (k + 1) % 3];
            const uint32_t wa = weldedIndex[a], wb = weldedIndex[b];
            if (wa == wb) continue;
            // Both sides list the edge's vertices in the same welded order.
            const bool flip = wa > wb;
            sides[{std::min(wa, wb), std::max(wa, wb)}].push_back(
                {uint32_t(t / 3), flip ? b : a, flip ? a : b});
        }
    std::vector<uint32_t> out;
    for (const auto& [edge, list] : sides) {
        if (list.size() != 2) continue;
        out.insert(out.end(), {list[0].triangle, list[1].triangle, list[0].a, list[0].b, list[1].a,
                               list[1].b});
    }
    return out;
}

SweptVolumePass::SweptVolumePass(const gpu::Context& ctx, const scene::Scene& scene,
                                 std::span<const anim::Character> cast,
                                 VkSampleCountFlagBits samples)
    : MeshEffectPass(ctx, cast) {
    for (Selected& selected : selectedEffects(scene)) {
        const Kind* kind = selected.kind;
        Effect effect(MeshEffect(ctx, selected.index, meshEffectColour(*kind),
                                 std::move(selected.source), 0, "swept"),
                      *kind);
        const trajectory::Source& source = effect.source;
        const uint32_t n = effect.vertexCount;
        effect.triangleCount = uint32_t(source.triangles.size() / 3);
        const std::vector<uint32_t> edges = sweptVolumeEdges(source.vertices, source.triangles);
        effect.edgeCount = uint32_t(edges.size() / 6);
        // Sec. 4.2: an n-segment sweep needs the positions at n + 1 times.
        effect.historySlots = kind->segments + 1;
        // Every edge joined and every triangle trailing: the most one frame can build.
        const VkDeviceSize outputCapacity =
            VkDeviceSize(effect.edgeCount) * 6 * kind->segments * kind->subSamples +
            VkDeviceSize(effect.triangleCount) * 3;

        effect.history = effectStorage(
            ctx, VkDeviceSize(n) * effect.historySlots * sizeof(glm::vec4), 0, "swept history");
        effect.triangles =
            effectStorage(ctx, source.triangles.size() * sizeof(uint32_t), 0, "swept triangles");
        if (!source.triangles.empty())
            gpu::uploadBuffer(ctx, effect.triangles, std::span<const uint32_t>(source.triangles));
        effect.edges = effectStorage(ctx, edges.size() * sizeof(uint32_t), 0, "swept edges");
        if (!edges.empty()) gpu::uploadBuffer(ctx, effect.edges, std::span<const uint32_t>(edges));
        effect.output = effectStorage(ctx, outputCapacity * sizeof(shared::TrajectoryVertex),
                                      VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "swept geometry");
        effect.counters =
            effectCounters(ctx, sizeof(shared::SweptVolumeCounters), "swept counters");
        effect.resources =
            gpu::bindBuffers({effect.skinned, effect.history, effect.colours, effect.triangles,
                              effect.edges, effect.output, effect.counters});
        effect.style = volumeStyleBuffer(ctx, kind->look);
        effects_.push_back(std::move(effect));
    }
    if (effects_.empty()) return; // a scene without the effect pays for nothing

    record_ = computeProgram(ctx, "swept_volume_record", shaders::swept_volume_record_comp);
    motion_ = computeProgram(ctx, "swept_volume_motion", shaders::swept_volume_motion_comp);
    build_ = computeProgram(ctx, "swept_volume_build", shaders::swept_volume_build_comp);

    // Translucent and unsorted, as the paper draws it (Sec. 5.1: few of its polygons overlap), so
    // it does not write depth.
    draw_ = trajectoryDrawProgram(ctx, "swept_volume", TrajectoryShape::Triangles, samples, false);
    frame_ = sceneFrameBuffer(ctx, "swept frame");
}

void SweptVolumePass::recordEffect(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                                   uint32_t frame, Effect& effect, bool reset) {
    const scene::Scene& scene = simulation.scene();
    const float time = simulation.frameTime(frame);
    effect.newest = reset ? 0 : (effect.newest + 1) % effect.historySlots;
    effect.filled = reset ? 1 : std::min(effect.filled + 1, effect.historySlots);

    shared::SweptVolumeCounters zero{};
    zero.instanceCount = 1;
    vkCmdUpdateBuffer(cmd, effect.counters.get(), 0, sizeof zero, &zero);
    transferToComputeBarrier(cmd);

    const scene::SweptVolumeSpec& e = effect.kind;
    shared::SweptVolumeConstants c{};
    c.cameraPosition = glm::vec4(camera_ ? camera_->eye : scene.camera.position, 1.0f);
    c.vertexCount = effect.vertexCount;
    c.triangleCount = effect.triangleCount;
    c.edgeCount = effect.edgeCount;
    c.historySlots = effect.historySlots;
    c.newest = effect.newest;
    c.filled = effect.filled;
    c.reset = reset ? 1 : 0;
    c.segments = e.segments;
    c.pieces = e.subSamples;
    c.temporalFilter = filterCode(e.filter);
    c.alphaFloor = e.alphaFloor;

    record_.bind(cmd, effect.resources);
    record_.push(cmd, c);
    vkCmdDispatch(cmd, gpu::groupCount(effect.vertexCount, MFX_SWEPT_GROUP_SIZE), 1, 1);
    // Outside its window the effect records its history (so it enters the window with the
    // right motion) but builds nothing.
    const bool live = simulation.effectLive(simulation.scene().effects[effect.index], time);
    if (!live) return;
    computeToComputeBarrier(cmd);
    motion_.bind(cmd, effect.resources);
    motion_.push(cmd, c);
    vkCmdDispatch(cmd, 1, 1, 1);
    computeToComputeBarrier(cmd);
    build_.bind(cmd, effect.resources);
    build_.push(cmd, c);
    vkCmdDispatch(
        cmd, gpu::groupCount(effect.edgeCount + effect.triangleCount, MFX_SWEPT_GROUP_SIZE), 1, 1);
}

SweptVolumePass::Counts SweptVolumePass::counts(size_t effect) const {
    const auto c = builtCounters<shared::SweptVolumeCounters>(effect);
    Counts out;
    out.vertices = c.vertexCount;
    out.contourEdges = c.contourEdges;
    out.trailingTriangles = c.trailingTriangles;
    out.motion = glm::vec3(c.motion);
    out.pathLength = c.motion.w;
    out.extent = c.extent;
    out.trailingAlpha = c.trailingAlpha;
    return out;
}

std::vector<shared::TrajectoryVertex> SweptVolumePass::geometry(size_t effect) const {
    return builtVertices(effect, counts(effect).vertices);
}

} // namespace mfx::render
