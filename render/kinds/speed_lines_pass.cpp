#include "render/kinds/speed_lines_pass.h"

#include "core/gpu/commands.h"
#include "shaders/embedded.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace mfx::render {

SpeedLinesPass::SpeedLinesPass(const gpu::Context& ctx, VkSampleCountFlagBits samples)
    : TrailEffectPass(
          ctx, scene::SpeedLinesSpec::kType,
          trajectoryDrawProgram(ctx, "effect_lines", TrajectoryShape::Ribbons, samples, false)),
      fadeDepthSource_(ctx), textureSource_(ctx) {
    joinsProgram_ = storageComputeProgram(ctx, "ribbon_joins", shaders::ribbon_joins_comp,
                                          sizeof(shared::RibbonJoinConstants));
    distanceProgram_ = storageComputeProgram(ctx, "ribbon_distance", shaders::ribbon_distance_comp,
                                             sizeof(shared::RibbonDistanceConstants));
    none_ = effectStorage(ctx, 64, 0, "speed-lines no joins");
    sheet_ = trajectoryDrawProgram(ctx, "effect_sheet", TrajectoryShape::Sheet, samples, false);
}

bool SpeedLinesPass::isSheet(const TrajectoryEffect& effect) {
    return effect.spec->as<scene::SpeedLinesSpec>()->ribbon.sheet;
}

const scene::RibbonTexture& SpeedLinesPass::textureOf(const TrajectoryEffect& effect) {
    return effect.spec->as<scene::SpeedLinesSpec>()->ribbon.texture;
}

bool SpeedLinesPass::tiledByDistance(const TrajectoryEffect& effect) {
    const scene::RibbonTexture& texture = textureOf(effect);
    return !texture.file.empty() && texture.uv == scene::TextureUv::Distance;
}

void SpeedLinesPass::advance(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                             uint32_t) {
    bool recorded = false;
    forEachEffect(simulation, [&](const TrajectoryEffect& effect) {
        if (tiledByDistance(effect) && advanceDistances(cmd, effect, simulation.serial()))
            recorded = true;
        if (!isSheet(effect) && advanceJoins(cmd, effect)) // a sheet's edges are its two lines
            recorded = true;
    });
    if (recorded) // the joins and distances, to the vertex stage that reads them
        gpu::memoryBarrier(
            cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
            VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

bool SpeedLinesPass::advanceJoins(VkCommandBuffer cmd, const TrajectoryEffect& effect) {
    const trajectory::Queue& queue = *effect.queue;
    Joins& joins = joins_[&queue];
    joins.framesRecorded = 0;
    const std::vector<trajectory::LiveSegment> live = queue.liveSegments(); // newest first
    if (live.empty()) return false;
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
    joinsProgram_.bind(cmd, {gpu::bindBuffer(0, queue.vertices()), gpu::bindBuffer(1, joins.chain),
                             gpu::bindBuffer(2, joins.directions)});
    joinsProgram_.push(cmd, c);
    const uint64_t invocations = uint64_t(c.segments) * c.sourceVertices * c.perLine;
    vkCmdDispatch(
        cmd,
        uint32_t((invocations + MFX_RIBBON_JOINS_GROUP_SIZE - 1) / MFX_RIBBON_JOINS_GROUP_SIZE), 1,
        1);
    joins.framesRecorded = queue.framesRecorded();
    return true;
}

bool SpeedLinesPass::advanceDistances(VkCommandBuffer cmd, const TrajectoryEffect& effect,
                                      uint64_t simulationSerial) {
    const trajectory::Queue& queue = *effect.queue;
    Distances& d = distances_[&queue];
    const VkDeviceSize ringVertices = queue.vertices().size / sizeof(shared::TrajectoryVertex);
    const uint32_t perSegment = queue.verticesPerSegment();
    const size_t slots = size_t(ringVertices / perSegment);
    if (!d.values || d.simulation != simulationSerial || d.slotFrame.size() != slots ||
        d.values.size < ringVertices * sizeof(float)) {
        d.values = effectStorage(ctx_, ringVertices * sizeof(float), 0, "speed-lines distances");
        d.segments =
            gpu::createBuffer(ctx_, slots * sizeof(glm::uvec2), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                              gpu::MemoryUsage::Upload, "speed-lines new segments");
        d.slotFrame.assign(slots, 0);
        d.simulation = simulationSerial;
    }
    // The live segments whose distances are still to be found, oldest first, each with its
    // predecessor where the line runs on from it (the frame just before, found earlier or above).
    const std::vector<trajectory::LiveSegment> live = queue.liveSegments(); // newest first
    auto* list = static_cast<glm::uvec2*>(d.segments.mapped);
    uint32_t count = 0;
    for (size_t i = live.size(); i-- > 0;) {
        const trajectory::LiveSegment& segment = live[i];
        const size_t slot = segment.firstVertex / perSegment;
        if (slot >= slots || d.slotFrame[slot] == segment.frame + 1) continue;
        const bool continues = i + 1 < live.size() && live[i + 1].frame + 1 == segment.frame;
        list[count++] = glm::uvec2(segment.firstVertex,
                                   continues ? live[i + 1].firstVertex : MFX_RIBBON_NO_SEGMENT);
        d.slotFrame[slot] = segment.frame + 1;
    }
    if (count == 0) return false;
    shared::RibbonDistanceConstants c{};
    c.sourceVertices = queue.sourceVertices();
    c.perLine = queue.subSamples() + 1;
    c.segments = count;
    distanceProgram_.bind(cmd, {gpu::bindBuffer(0, queue.vertices()),
                                gpu::bindBuffer(1, d.segments), gpu::bindBuffer(2, d.values)});
    distanceProgram_.push(cmd, c);
    vkCmdDispatch(cmd,
                  (c.sourceVertices + MFX_RIBBON_DISTANCE_GROUP_SIZE - 1) /
                      MFX_RIBBON_DISTANCE_GROUP_SIZE,
                  1, 1);
    return true;
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
SpeedLinesPass::textureBindings(const sim::SceneSimulation& simulation,
                                const TrajectoryEffect& effect) {
    const scene::RibbonTexture& texture = textureOf(effect);
    if (texture.file.empty()) return textureSource_.none();
    const size_t index = simulation.effectIndex(effect);
    const std::string file = scene::textureFile(simulation.scene(), texture.file).string();
    auto image = textures_.find(file);
    if (image == textures_.end()) {
        // The scene's loading checked the file; should it have changed since, the effect is drawn
        // without its texture rather than not at all.
        Result<scene::TextureImage> loaded = scene::loadEffectTexture(simulation.scene(), index);
        gpu::Image made;
        if (loaded) {
            made = RibbonTextureSource::upload(ctx_, loaded.value(), "speed-lines texture");
        } else {
            std::fprintf(stderr, "warning: %s (drawn without it)\n",
                         loaded.error().message.c_str());
        }
        image = textures_.emplace(file, std::move(made)).first;
    }
    const auto d = distances_.find(effect.queue.get());
    const gpu::Buffer* distances =
        tiledByDistance(effect) && d != distances_.end() ? &d->second.values : nullptr;
    return {
        textureSource_.distances(distances),
        textureSource_.texture(image->second.get() != VK_NULL_HANDLE ? &image->second : nullptr)};
}

std::vector<gpu::DescriptorWrite>
SpeedLinesPass::extraBindings(const sim::SceneSimulation& simulation,
                              const TrajectoryEffect& effect) {
    std::vector<gpu::DescriptorWrite> writes = {fadeDepthSource_.binding(fadeDepth_)};
    if (isSheet(effect)) { // the ring, for each vertex's partner on the other line
        writes.push_back(gpu::bindBuffer(3, effect.queue->vertices()));
    } else {
        const Joins* joins = joinsFor(effect);
        writes.push_back(gpu::bindBuffer(3, joins ? joins->directions : none_));
    }
    for (const gpu::DescriptorWrite& w : textureBindings(simulation, effect))
        writes.push_back(w);
    return writes;
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
    // Stretch maps the texture once over the live ribbon's age span: from now back to its oldest
    // sample, a frame before its oldest segment's time.
    const float now = draw.timing.x, dt = draw.timing.w;
    float span = dt;
    if (lines.ribbon.texture.uv == scene::TextureUv::Stretch) {
        const std::vector<trajectory::LiveSegment> live = effect.queue->liveSegments();
        if (!live.empty()) span = now - (live.back().birth - dt);
    }
    // A distance-tiled texture without its distances (none found yet) is not drawn as one.
    setRibbonTexture(draw, lines.ribbon, now, span, draw.timing.y);
    if (tiledByDistance(effect) && !distances_.count(effect.queue.get()))
        draw.ribbonTexture.x = 0.0f;
}

} // namespace mfx::render
