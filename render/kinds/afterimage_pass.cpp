#include "render/kinds/afterimage_pass.h"

#include <limits>

#include "core/gpu/check.h"
#include "core/gpu/context.h"
#include "render/effect_geometry.h"
#include "render/render_target.h"
#include "shaders/embedded.h"
#include "shaders/shared/effect_draw.h"
#include "sim/scene_simulation.h"

#include <algorithm>
#include <cstring>
#include <set>
#include <utility>

namespace mfx::render {

namespace {

gpu::Program computeProgram(const gpu::Context& ctx, const char* name,
                            std::span<const uint32_t> spirv) {
    return storageComputeProgram(ctx, name, spirv, sizeof(shared::AfterimageConstants));
}

// The edges of a triangle list, each once (Smith 2016, Sec. 5.1.2: the adjacency the arcs'
// quads are built on).
std::vector<uint32_t> uniqueEdges(const std::vector<uint32_t>& triangles) {
    std::set<std::pair<uint32_t, uint32_t>> edges;
    for (size_t t = 0; t + 2 < triangles.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = triangles[t + size_t(k)], b = triangles[t + size_t((k + 1) % 3)];
            if (a != b) edges.emplace(std::min(a, b), std::max(a, b));
        }
    std::vector<uint32_t> out;
    out.reserve(edges.size() * 2);
    for (const auto& [a, b] : edges) {
        out.push_back(a);
        out.push_back(b);
    }
    return out;
}

} // namespace

std::vector<uint32_t> afterimageCopies(const std::vector<shared::SkinVertexIn>& vertices) {
    const Welding welding = weldByPosition(vertices);
    std::vector<std::vector<uint32_t>> groups(welding.groupCount);
    for (size_t v = 0; v < vertices.size(); ++v)
        groups[welding.group[v]].push_back(uint32_t(v));
    std::vector<uint32_t> out(vertices.size() + 1);
    uint32_t at = uint32_t(out.size());
    for (size_t v = 0; v < vertices.size(); ++v) {
        out[v] = at;
        at += uint32_t(groups[welding.group[v]].size());
    }
    out[vertices.size()] = at;
    for (size_t v = 0; v < vertices.size(); ++v) {
        const std::vector<uint32_t>& group = groups[welding.group[v]];
        out.insert(out.end(), group.begin(), group.end());
    }
    return out;
}

AfterimagePass::AfterimagePass(const gpu::Context& ctx, const scene::Scene& scene,
                               std::span<const anim::Character> cast, VkSampleCountFlagBits samples)
    : MeshEffectPass(ctx, cast), fadeDepthSource_(ctx), textureSource_(ctx) {
    for (Selected& selected : selectedEffects(scene)) {
        const Kind* kind = selected.kind;
        Effect effect(MeshEffect(ctx, selected.index, meshEffectColour(*kind),
                                 std::move(selected.source), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                                 "afterimage"),
                      *kind);
        const trajectory::Source& source = effect.source;
        const scene::AfterimageVariant variant = kind->variant;
        // Smith 2016, Sec. 4.1.1: one afterimage needs the last frame only; an arc through n
        // afterimages needs the n frames before this one.
        effect.historySlots =
            variant == scene::AfterimageVariant::Multi ? kind->afterimages + 1 : 2;
        const uint32_t n = effect.vertexCount;
        std::vector<uint32_t> primitives;
        if (variant == scene::AfterimageVariant::Smear) {
            primitives = source.triangles;
            effect.primitiveCount = uint32_t(primitives.size() / 3);
        } else if (variant == scene::AfterimageVariant::Multi) {
            primitives = uniqueEdges(source.triangles);
            effect.primitiveCount = uint32_t(primitives.size() / 2);
        }
        effect.outputCapacity = variant == scene::AfterimageVariant::SpeedLines ? 2 * n
                                : variant == scene::AfterimageVariant::Multi
                                    ? effect.primitiveCount * 6 * kind->afterimages
                                    : 0;

        effect.history =
            effectStorage(ctx, VkDeviceSize(n) * effect.historySlots * sizeof(glm::vec4), 0,
                          "afterimage history");
        effect.pushed = effectStorage(ctx, n * sizeof(shared::TrajectoryVertex),
                                      VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "afterimage pushed");
        effect.decided =
            effectStorage(ctx, n * sizeof(shared::TrajectoryVertex), 0, "afterimage decided");
        effect.copyTable = afterimageCopies(source.vertices);
        effect.copies =
            effectStorage(ctx, effect.copyTable.size() * sizeof(uint32_t), 0, "afterimage copies");
        gpu::uploadBuffer(ctx, effect.copies, std::span<const uint32_t>(effect.copyTable));
        effect.primitives =
            effectStorage(ctx, primitives.size() * sizeof(uint32_t), 0, "afterimage primitives");
        if (!primitives.empty())
            gpu::uploadBuffer(ctx, effect.primitives, std::span<const uint32_t>(primitives));
        effect.output = effectStorage(
            ctx, VkDeviceSize(effect.outputCapacity) * sizeof(shared::TrajectoryVertex),
            VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "afterimage geometry");
        effect.indices = effectStorage(ctx,
                                       variant == scene::AfterimageVariant::Smear
                                           ? source.triangles.size() * sizeof(uint32_t)
                                           : 0,
                                       VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "afterimage indices");
        effect.counters =
            effectCounters(ctx, sizeof(shared::AfterimageCounters), "afterimage counters");
        effect.resources = gpu::bindBuffers(
            {effect.skinned, effect.history, effect.colours, effect.pushed, effect.primitives,
             effect.output, effect.indices, effect.counters, effect.decided, effect.copies});
        effect.style = variant == scene::AfterimageVariant::SpeedLines
                           ? ribbonStyleBuffer(ctx, kind->ribbon)
                           : volumeStyleBuffer(ctx, kind->look);
        effects_.push_back(std::move(effect));
    }
    if (effects_.empty()) return; // a scene without the effect pays for nothing

    record_ = computeProgram(ctx, "afterimage_record", shaders::afterimage_record_comp);
    smear_ = computeProgram(ctx, "afterimage_smear", shaders::afterimage_smear_comp);
    weld_ = computeProgram(ctx, "afterimage_weld", shaders::afterimage_weld_comp);
    build_ = computeProgram(ctx, "afterimage_build", shaders::afterimage_build_comp);

    // The smear is by default an opaque copy of the mesh: it writes depth.
    smearDraw_ =
        trajectoryDrawProgram(ctx, "afterimage_smear", TrajectoryShape::Triangles, samples, true);
    lineDraw_ =
        trajectoryDrawProgram(ctx, "afterimage_lines", TrajectoryShape::Ribbons, samples, false);
    arcDraw_ =
        trajectoryDrawProgram(ctx, "afterimage_arcs", TrajectoryShape::Triangles, samples, false);
    frame_ = sceneFrameBuffer(ctx, "afterimage frame");
    noJoins_ = effectStorage(ctx, 64, 0, "afterimage lines no joins");
}

void AfterimagePass::beginFrame(const sim::SceneSimulation& simulation, bool reset) {
    // The whole character's motion (m^U of Smith 2016, Sec. 4.3): its root's travel this frame,
    // for each character.
    const size_t n = simulation.cast().size();
    lastRoots_.resize(n, glm::vec3(0.0f));
    characterMotions_.resize(n, glm::vec3(0.0f));
    for (size_t c = 0; c < n; ++c) {
        const glm::vec3 root = simulation.rootPosition(c, simulation.framePose(c));
        characterMotions_[c] = reset ? glm::vec3(0.0f) : root - lastRoots_[c];
        lastRoots_[c] = root;
    }
}

void AfterimagePass::recordEffect(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                                  uint32_t frame, Effect& effect, bool reset) {
    const scene::Scene& scene = simulation.scene();
    const float time = simulation.frameTime(frame);
    effect.newest = reset ? 0 : (effect.newest + 1) % effect.historySlots;
    effect.filled = reset ? 1 : std::min(effect.filled + 1, effect.historySlots);

    shared::AfterimageCounters zero{};
    zero.indexedInstanceCount = 1;
    zero.instanceCount = 1;
    vkCmdUpdateBuffer(cmd, effect.counters.get(), 0, sizeof zero, &zero);
    transferToComputeBarrier(cmd);

    const scene::AfterimageSpec& a = effect.kind;
    shared::AfterimageConstants c{};
    const size_t follows = scene::effectCharacter(scene, scene.effects[effect.index]);
    c.characterMotion = glm::vec4(
        follows < characterMotions_.size() ? characterMotions_[follows] : glm::vec3(0.0f), 0.0f);
    c.vertexCount = effect.vertexCount;
    c.primitiveCount = effect.primitiveCount;
    c.historySlots = effect.historySlots;
    c.newest = effect.newest;
    c.filled = effect.filled;
    c.reset = reset ? 1 : 0;
    c.variant = a.variant == scene::AfterimageVariant::Smear        ? MFX_AFTERIMAGE_SMEAR
                : a.variant == scene::AfterimageVariant::SpeedLines ? MFX_AFTERIMAGE_SPEED_LINES
                                                                    : MFX_AFTERIMAGE_MULTI;
    c.afterimages = a.afterimages;
    c.strengthCharacter = a.strengthCharacter;
    c.strengthAnimation = a.strengthAnimation;
    c.randomMin = a.randomMin;
    c.randomMax = a.randomMax;
    c.randomThreshold = a.randomThreshold;
    c.taper = a.taper;
    c.minSpeed = a.minSpeed / scene.output.fps; // per second → per frame
    c.relativeSpeed = a.relativeSpeed;
    c.alphaStart = a.alphaStart;
    c.alphaEnd = a.alphaEnd;
    c.alphaPower = a.alphaPower;
    c.influencePower = a.influencePower;
    c.stride = a.stride;

    const uint32_t vertexGroups = gpu::groupCount(effect.vertexCount, MFX_AFTERIMAGE_GROUP_SIZE);
    record_.bind(cmd, effect.resources);
    record_.push(cmd, c);
    vkCmdDispatch(cmd, vertexGroups, 1, 1);
    // Outside its window the effect records its history (so it enters the window with the
    // right motion) but builds nothing.
    const bool live = simulation.effectLive(simulation.scene().effects[effect.index], time);
    if (live) {
        computeToComputeBarrier(cmd);
        smear_.bind(cmd, effect.resources);
        smear_.push(cmd, c);
        vkCmdDispatch(cmd, vertexGroups, 1, 1);
        computeToComputeBarrier(cmd);
        weld_.bind(cmd, effect.resources);
        weld_.push(cmd, c);
        vkCmdDispatch(cmd, vertexGroups, 1, 1);
        if (effect.primitiveCount > 0) {
            computeToComputeBarrier(cmd);
            build_.bind(cmd, effect.resources);
            build_.push(cmd, c);
            vkCmdDispatch(cmd, gpu::groupCount(effect.primitiveCount, MFX_AFTERIMAGE_GROUP_SIZE), 1,
                          1);
        }
    }
}

uint32_t AfterimagePass::draw(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                              const SceneCamera& camera, float, std::span<const uint8_t> shown) {
    const scene::Scene& scene = simulation.scene();
    if (effects_.empty() || !history_.recorded()) return 0;
    const shared::SceneFrame frame = sceneFrame(scene, camera);
    std::memcpy(frame_.mapped, &frame, sizeof frame);
    uint32_t draws = 0;
    const VkDeviceSize offset = 0;
    for (const Effect& effect : effects_) {
        if (!effectShown(shown, effect.index)) continue;
        const scene::AfterimageVariant variant = effect.kind.variant;
        const bool lines = variant == scene::AfterimageVariant::SpeedLines;
        const scene::RibbonLook& ribbon = effect.kind.ribbon;
        // Every vertex is drawn at time 0: the alpha along the push or the arc is in the vertex
        // colour. A speed-line's pushed end has sample time -1 (afterimage_smear.comp): with a
        // lifetime of 1 its life u runs from 0 at the mesh to 1 there, for the ribbon's
        // colour_over_life and width_over_life; without either no age fade (an endless lifetime).
        // The smear's and the arcs' life is the place along the push or the arc (position.w).
        const bool overLife = !ribbon.colourOverLife.empty() || !ribbon.widthOverLife.empty();
        shared::EffectDraw d{};
        d.timing = glm::vec4(0.0f, lines && overLife ? 1.0f : std::numeric_limits<float>::max(),
                             effect.kind.width, 1.0f / scene.output.fps);
        d.tint = glm::vec4(1.0f);
        if (lines)
            setRibbonLook(d, ribbon);
        else
            setVolumeLook(d, effect.kind.look, true);
        if (variant == scene::AfterimageVariant::Smear) {
            smearDraw_.bind(cmd, {gpu::bindBuffer(0, frame_), gpu::bindBuffer(1, effect.style)});
            smearDraw_.push(cmd, d);
            VkBuffer vb = effect.pushed.get();
            vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
            vkCmdBindIndexBuffer(cmd, effect.indices.get(), 0, VK_INDEX_TYPE_UINT32);
            vkCmdDrawIndexedIndirect(cmd, effect.counters.get(), 0, 1,
                                     sizeof(VkDrawIndexedIndirectCommand));
        } else {
            gpu::Program& program = lines ? lineDraw_ : arcDraw_;
            // The lines have no joins (ribbonShape.x = 0) and no texture (ribbonTexture.x = 0):
            // bindings 3 to 5 are bound, never read.
            if (lines)
                program.bind(cmd,
                             {gpu::bindBuffer(0, frame_), gpu::bindBuffer(1, effect.style),
                              fadeDepthSource_.binding(fadeDepth_), gpu::bindBuffer(3, noJoins_),
                              textureSource_.distances(nullptr), textureSource_.texture(nullptr)});
            else
                program.bind(cmd, {gpu::bindBuffer(0, frame_), gpu::bindBuffer(1, effect.style)});
            program.push(cmd, d);
            VkBuffer vb = effect.output.get();
            vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
            vkCmdDrawIndirect(cmd, effect.counters.get(),
                              offsetof(shared::AfterimageCounters, vertexCount), 1,
                              sizeof(VkDrawIndirectCommand));
        }
        ++draws;
    }
    return draws;
}

AfterimagePass::Counts AfterimagePass::counts(size_t effect) const {
    const auto c = builtCounters<shared::AfterimageCounters>(effect);
    Counts out;
    out.pushedVertices = c.pushedVertices;
    out.triangles = c.indexCount / 3;
    out.lineVertices = c.vertexCount;
    std::memcpy(&out.fastest, &c.fastestBits, sizeof(float));
    return out;
}

AfterimagePass::Decisions AfterimagePass::decisions(size_t effect) const {
    const Effect* e = find(effect);
    if (!e) return {};
    Decisions out;
    out.decided = gpu::readBufferAs<shared::TrajectoryVertex>(ctx_, e->decided);
    out.drawn = gpu::readBufferAs<shared::TrajectoryVertex>(ctx_, e->pushed);
    out.decided.resize(e->vertexCount);
    out.drawn.resize(e->vertexCount);
    out.copies = e->copyTable;
    return out;
}

std::vector<shared::TrajectoryVertex> AfterimagePass::geometry(size_t effect) const {
    const Effect* e = find(effect);
    if (!e) return {};
    const Counts c = counts(effect);
    if (e->kind.variant == scene::AfterimageVariant::Smear) {
        const auto vertices = gpu::readBufferAs<shared::TrajectoryVertex>(ctx_, e->pushed);
        const auto indices = gpu::readBufferAs<uint32_t>(ctx_, e->indices);
        std::vector<shared::TrajectoryVertex> out;
        for (uint32_t k = 0; k < c.triangles * 3 && k < indices.size(); ++k)
            out.push_back(vertices[indices[k]]);
        return out;
    }
    return builtVertices(effect, c.lineVertices);
}

} // namespace mfx::render
