#include "render/kinds/speed_lines_pass.h"

#include "core/gpu/commands.h"
#include "shaders/embedded.h"

#include <algorithm>
#include <cstring>

namespace mfx::render {

SpeedLinesPass::SpeedLinesPass(const gpu::Context& ctx, VkSampleCountFlagBits samples)
    : TrailEffectPass(
          ctx, scene::SpeedLinesSpec::kType,
          trajectoryDrawProgram(ctx, "effect_lines", TrajectoryShape::Ribbons, samples, false)),
      fadeDepthSource_(ctx) {
    joinsProgram_ = storageComputeProgram(ctx, "ribbon_joins", shaders::ribbon_joins_comp,
                                          sizeof(shared::RibbonJoinConstants));
    none_ = effectStorage(ctx, 64, 0, "speed-lines no joins");
    sheet_ = trajectoryDrawProgram(ctx, "effect_sheet", TrajectoryShape::Sheet, samples, false);
}

bool SpeedLinesPass::isSheet(const TrajectoryEffect& effect) {
    return effect.spec->as<scene::SpeedLinesSpec>()->ribbon.sheet;
}

void SpeedLinesPass::advance(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                             uint32_t) {
    bool recorded = false;
    forEachEffect(simulation, [&](const TrajectoryEffect& effect) {
        if (isSheet(effect)) return; // its edges are its two lines
        const trajectory::Queue& queue = *effect.queue;
        Joins& joins = joins_[&queue];
        joins.framesRecorded = 0;
        const std::vector<trajectory::LiveSegment> live = queue.liveSegments(); // newest first
        if (live.empty()) return;
        const VkDeviceSize ringVertices = queue.vertices().size / sizeof(shared::TrajectoryVertex);
        const VkDeviceSize chainBytes =
            std::max<VkDeviceSize>(queue.options().maxLifetime, live.size()) * sizeof(glm::uvec2);
        if (!joins.directions || joins.directions.size < ringVertices * sizeof(glm::vec4) ||
            joins.chain.size < chainBytes) {
            joins.directions =
                effectStorage(ctx_, ringVertices * sizeof(glm::vec4), 0, "speed-lines joins");
            joins.chain = gpu::createBuffer(ctx_, chainBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                            gpu::MemoryUsage::Upload, "speed-lines chain");
        }
        // Segment i continues into segment i + 1 where that is the frame just before it.
        auto* chain = static_cast<glm::uvec2*>(joins.chain.mapped);
        for (size_t i = 0; i < live.size(); ++i)
            chain[i] = glm::uvec2(live[i].firstVertex,
                                  i + 1 < live.size() && live[i + 1].frame + 1 == live[i].frame);
        shared::RibbonJoinConstants c{};
        c.perLine = queue.subSamples() + 1;
        c.sourceVertices = queue.sourceVertices();
        c.segments = uint32_t(live.size());
        joinsProgram_.bind(cmd,
                           {gpu::bindBuffer(0, queue.vertices()), gpu::bindBuffer(1, joins.chain),
                            gpu::bindBuffer(2, joins.directions)});
        joinsProgram_.push(cmd, c);
        const uint64_t invocations = uint64_t(c.segments) * c.sourceVertices * c.perLine;
        vkCmdDispatch(
            cmd,
            uint32_t((invocations + MFX_RIBBON_JOINS_GROUP_SIZE - 1) / MFX_RIBBON_JOINS_GROUP_SIZE),
            1, 1);
        joins.framesRecorded = queue.framesRecorded();
        recorded = true;
    });
    if (recorded) // the joins, to the vertex stage that reads them
        gpu::memoryBarrier(
            cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
            VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

const SpeedLinesPass::Joins* SpeedLinesPass::joinsFor(const TrajectoryEffect& effect) const {
    const auto j = joins_.find(effect.queue.get());
    const bool current = j != joins_.end() && j->second.framesRecorded != 0 &&
                         j->second.framesRecorded == effect.queue->framesRecorded();
    return current ? &j->second : nullptr;
}

gpu::Buffer SpeedLinesPass::makeStyle(const scene::EffectSpec& spec) const {
    return ribbonStyleBuffer(ctx_, spec.as<scene::SpeedLinesSpec>()->ribbon);
}

std::vector<gpu::DescriptorWrite>
SpeedLinesPass::extraBindings(const TrajectoryEffect& effect) const {
    if (isSheet(effect)) // the ring, for each vertex's partner on the other line
        return {fadeDepthSource_.binding(fadeDepth_), gpu::bindBuffer(3, effect.queue->vertices())};
    const Joins* joins = joinsFor(effect);
    return {fadeDepthSource_.binding(fadeDepth_),
            gpu::bindBuffer(3, joins ? joins->directions : none_)};
}

TrailEffectPass::DrawSource SpeedLinesPass::drawSource(const TrajectoryEffect& effect) {
    if (!isSheet(effect)) return TrailEffectPass::drawSource(effect);
    // Sample j of the first line is vertex j, of the second S + 1 + j: piece j is the quad
    // (j, j + 1) x (first, second), two triangles.
    const uint32_t pieces = effect.queue->subSamples();
    auto indices = sheetIndices_.find(pieces);
    if (indices == sheetIndices_.end()) {
        std::vector<uint32_t> values;
        for (uint32_t j = 0; j < pieces; ++j) {
            const uint32_t a = j, b = j + 1, c = pieces + 1 + j, d = pieces + 2 + j;
            for (uint32_t v : {a, c, b, b, c, d})
                values.push_back(v);
        }
        gpu::Buffer buffer = gpu::createBuffer(
            ctx_, values.size() * sizeof(uint32_t), VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
            gpu::MemoryUsage::Upload, "speed-line sheet indices");
        std::memcpy(buffer.mapped, values.data(), values.size() * sizeof(uint32_t));
        indices = sheetIndices_.emplace(pieces, std::move(buffer)).first;
    }
    DrawSource source;
    source.program = &sheet_;
    source.indices = indices->second.get();
    source.indexCount = 6 * pieces;
    return source;
}

void SpeedLinesPass::setLook(shared::EffectDraw& draw, const TrajectoryEffect& effect) const {
    const auto& lines = *effect.spec->as<scene::SpeedLinesSpec>();
    draw.timing.z = lines.width;
    setRibbonLook(draw, lines.ribbon);
    draw.ribbonShape.x = joinsFor(effect) ? 1.0f : 0.0f;
    draw.ribbonShape.y = float(effect.queue->subSamples() + 1);
}

} // namespace mfx::render
