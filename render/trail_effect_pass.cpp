#include "render/trail_effect_pass.h"

#include <cstring>

namespace mfx::render {

TrailEffectPass::TrailEffectPass(const gpu::Context& ctx, const char* type, gpu::Program program)
    : ctx_(ctx), type_(type), program_(std::move(program)) {
    frame_ = sceneFrameBuffer(ctx, (type_ + " frame").c_str());
}

uint32_t TrailEffectPass::draw(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                               const SceneCamera& camera, float now,
                               std::span<const uint8_t> shown) {
    const shared::SceneFrame frame = sceneFrame(simulation.scene(), camera);
    std::memcpy(frame_.mapped, &frame, sizeof frame);
    const float fps = simulation.scene().output.fps;
    uint32_t draws = 0;
    forEachEffect(simulation, [&](const TrajectoryEffect& effect) {
        const size_t index = simulation.effectIndex(effect);
        if (!effectShown(shown, index)) return;
        const trajectory::Queue& queue = *effect.queue;
        const std::vector<trajectory::LiveSegment> live = queue.liveSegments();
        if (live.empty()) return;
        auto style = styles_.find(index);
        if (style == styles_.end()) style = styles_.emplace(index, makeStyle(*effect.spec)).first;
        std::vector<gpu::DescriptorWrite> writes = {gpu::bindBuffer(0, frame_),
                                                    gpu::bindBuffer(1, style->second)};
        for (const gpu::DescriptorWrite& w : extraBindings(simulation, effect))
            writes.push_back(w);
        const DrawSource source = drawSource(effect);
        const gpu::Program& program = *source.program;
        program.bind(cmd, writes);
        shared::EffectDraw d{};
        d.timing = glm::vec4(now, float(effect.trail->lifetime) / fps, 0.0f, 1.0f / fps);
        d.tint = glm::vec4(1.0f);
        setLook(d, effect);
        program.push(cmd, d);
        const VkBuffer vertices = queue.vertices().get();
        const VkDeviceSize offset = 0;
        vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
        const bool indexed = source.indices != VK_NULL_HANDLE;
        if (indexed) vkCmdBindIndexBuffer(cmd, source.indices, 0, VK_INDEX_TYPE_UINT32);
        for (const trajectory::LiveSegment& segment : live) {
            if (indexed)
                vkCmdDrawIndexed(cmd, source.indexCount, 1, 0, int32_t(segment.firstVertex), 0);
            else
                vkCmdDraw(cmd, queue.verticesPerSegment(), 1, segment.firstVertex, 0);
            ++draws;
        }
    });
    return draws;
}

TrailEffectPass::DrawSource TrailEffectPass::drawSource(const TrajectoryEffect& effect) {
    const trajectory::Queue& queue = *effect.queue;
    DrawSource source;
    source.program = &program_;
    if (queue.indicesPerSegment() > 0) {
        source.indices = queue.indices().get();
        source.indexCount = queue.indicesPerSegment();
    }
    return source;
}

} // namespace mfx::render
