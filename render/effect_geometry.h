// What the passes that build effect geometry on the GPU and draw it by indirect draws share
// (render/kinds/afterimage_pass.h, render/kinds/swept_volume_pass.h,
// render/kinds/silhouette_shell_pass.h): the skinning of an effect's bound vertices, compute
// programs over storage buffers, the pipelines that draw trajectory vertices and the unsorted draw
// of built triangles, the barriers between building and drawing, and the rule that decides when a
// per-frame history starts again.
#pragma once

#include "core/scene/kinds/trail_effects.h"
#include "core/scene/ribbon_texture.h"

#include "core/anim/skin_vertices.h"
#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/scene/effect_source.h"
#include "core/scene/scene.h"
#include "core/trajectory/trajectory_source.h"
#include "render/scene_camera.h"
#include "shaders/shared/effect_draw.h"
#include "shaders/shared/skinning.h"

#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <vector>

namespace mfx::render {

// Whether the effect at `index` in scene.effects is drawn: `shown` empty (all are) or non-zero at
// that index.
inline bool effectShown(std::span<const uint8_t> shown, size_t index) {
    return shown.empty() || (index < shown.size() && shown[index] != 0);
}

// The entry of a pass's `effects` whose `index` (in scene.effects) is `index`; null if none.
template <class Effect>
const Effect* findEffect(const std::vector<Effect>& effects, size_t index) {
    for (const Effect& e : effects)
        if (e.index == index) return &e;
    return nullptr;
}

// A compute program of an effect's history (its bindings read from `spirv`).
gpu::Program storageComputeProgram(const gpu::Context& ctx, const char* name,
                                   std::span<const uint32_t> spirv, uint32_t pushConstantSize);

// What a trajectory draw makes of its vertices (shaders/render/effect_*): lit triangles, line
// pieces widened into camera-facing ribbons, points as round sprites, or the triangles of a
// speed-line sheet between two lines (effect_sheet.vert; the ring itself at binding 3).
enum class TrajectoryShape { Triangles, Ribbons, Sprites, Sheet };

// A pipeline drawing shared::TrajectoryVertex as the trajectory effects' passes do
// (render/trail_effect_pass.h): the scene frame at binding 0, shared::EffectDraw as push
// constants, premultiplied alpha, depth tested, the effect shaders of `shape`.
gpu::Program trajectoryDrawProgram(const gpu::Context& ctx, const char* name, TrajectoryShape shape,
                                   VkSampleCountFlagBits samples, bool depthWrite);

// The host-visible uniform a pass writes shared::SceneFrame into each draw.
gpu::Buffer sceneFrameBuffer(const gpu::Context& ctx, const char* name);

// The style (binding 1, shaders/render/ribbon_style.glsl) of the speed-line and particle programs
// for `look`, and of the volume program for a volume's look, in a host-visible uniform buffer.
gpu::Buffer ribbonStyleBuffer(const gpu::Context& ctx, const scene::RibbonLook& look);
gpu::Buffer volumeStyleBuffer(const gpu::Context& ctx, const scene::VolumeLook& look);
// The look's switches and light in a draw's push constants: a speed-line or particle draw's, and
// a volume's, whose life is the age or, with `lifeFromPlace`, the place along the sweep.
void setRibbonLook(shared::EffectDraw& draw, const scene::RibbonLook& look);
void setVolumeLook(shared::EffectDraw& draw, const scene::VolumeLook& look, bool lifeFromPlace);

// What the speed-line and particle programs read at binding 2 (shaders/render/depth_fade.glsl):
// the frame's copy of the scene's depth when it has one (EffectKindPass::setFadeDepth), else a
// 1x1 depth image at the far plane.
class FadeDepthSource {
public:
    explicit FadeDepthSource(const gpu::Context& ctx);
    gpu::DescriptorWrite binding(const gpu::Image* sceneDepth) const;

private:
    gpu::Image far_;
    gpu::UniqueSampler sampler_;
};

// What the speed-line programs read at bindings 4 and 5 (shaders/render/ribbon_texture.glsl): the
// ribbon's distances along its lines (a storage buffer) and its texture (sRGB RGBA8, bilinear,
// repeating), or stand-ins a draw without them binds (never read: its texture mode is 0).
class RibbonTextureSource {
public:
    explicit RibbonTextureSource(const gpu::Context& ctx);
    // The texture's texels in a sampled image.
    static gpu::Image upload(const gpu::Context& ctx, const scene::TextureImage& texture,
                             const char* name);
    gpu::DescriptorWrite distances(const gpu::Buffer* distances) const;
    gpu::DescriptorWrite texture(const gpu::Image* texture) const;
    // Both stand-ins.
    std::vector<gpu::DescriptorWrite> none() const {
        return {distances(nullptr), texture(nullptr)};
    }

private:
    gpu::Image white_;
    gpu::Buffer noDistances_;
    gpu::UniqueSampler sampler_;
};

// The texture's mode, scale, scroll and erosion in a speed-line draw's push constants
// (EffectDraw::ribbonTexture) at scene time `now`; `ageSpan` is the live ribbon's (stretch) and
// `lifetime` the trail's, in seconds. Mode 0 where the look has no texture.
void setRibbonTexture(shared::EffectDraw& draw, const scene::RibbonLook& look, float now,
                      float ageSpan, float lifetime);

// A device-local storage buffer (at least 64 bytes, so an empty one is still valid) that can also
// be copied to and from, with `extra` usage.
gpu::Buffer effectStorage(const gpu::Context& ctx, VkDeviceSize bytes, VkBufferUsageFlags extra,
                          const char* name);

// A build's counters and indirect draw arguments: a zeroed storage buffer the host reads back,
// usable as indirect arguments and written by transfers.
gpu::Buffer effectCounters(const gpu::Context& ctx, VkDeviceSize bytes, const char* name);

// What every mesh-effect pass keeps of one of its effects: the bound vertices (`source`), their
// bind pose (`input`), skinning palette and skinned vertices, their colours (the mesh's, or the
// effect's colour where it has one), the built geometry and its counters, and what each of
// the effect's compute programs binds. A pass's own effect struct derives from it.
struct MeshEffect {
    MeshEffect() = default;
    // Makes input, palette, skinned (with `skinnedUsage` as well) and colours, named "<label> bind
    // pose", "<label> palette", ...; output, counters and resources are the pass's to make.
    MeshEffect(const gpu::Context& ctx, size_t index, std::optional<glm::vec4> colour,
               trajectory::Source source, VkBufferUsageFlags skinnedUsage, const char* label);

    // Records the skinning of the bound vertices in `pose`, the character placed by `placement`,
    // into `skinned`. The palette is written now: the previous recording that used it must have
    // finished executing.
    void skin(VkCommandBuffer cmd, anim::SkinVertices& skinning, const anim::Character& character,
              const anim::Pose& pose, const glm::mat4& placement) const;

    size_t index = 0; // in scene.effects
    trajectory::Source source;
    uint32_t vertexCount = 0;
    gpu::Buffer input, palette, skinned, colours, output, counters;
    gpu::Buffer style; // the look's (ribbon_style.glsl): the pass makes it from its kind's look
    std::vector<gpu::DescriptorWrite> resources;
};

// A mesh effect's colour: its kind's, or none (the mesh's own) where the scene gave none.
template <class Kind>
std::optional<glm::vec4> meshEffectColour(const Kind& kind) {
    return kind.useMeshColour ? std::nullopt : std::optional<glm::vec4>(kind.colour);
}

// Records the unsorted, non-indexed draw of the triangles a build wrote into `vertices`, its
// VkDrawIndirectCommand at the start of `counters`, with `look` (its life the place along the
// sweep) and its `style` buffer. Every vertex is drawn at time 0 with sample time 0, so
// effect_common.glsl applies no age fade: the alpha is in the vertex colour.
void drawBuiltTriangles(VkCommandBuffer cmd, gpu::Program& program, const gpu::Buffer& frame,
                        const gpu::Buffer& vertices, const gpu::Buffer& counters, float fps,
                        const scene::VolumeLook& look, const gpu::Buffer& style);

// The copies of a vertex at one bind-pose position (a seam: one point with several normals) welded
// into one: each vertex's group, groups numbered in order of first appearance, exact positions.
struct Welding {
    std::vector<uint32_t> group; // per vertex
    uint32_t groupCount = 0;
};
Welding weldByPosition(std::span<const shared::SkinVertexIn> vertices);

// Writes the scene frame of `camera` into `frame` (host-visible) and draws the built triangles of
// each shown entry of `effects` (their `output` and `counters`) with `program`, which binds the
// frame. Returns the number of draws.
template <class Effect>
uint32_t drawBuiltEffects(VkCommandBuffer cmd, const std::vector<Effect>& effects,
                          const scene::Scene& scene, const SceneCamera& camera,
                          std::span<const uint8_t> shown, const gpu::Buffer& frame,
                          gpu::Program& program) {
    const shared::SceneFrame values = sceneFrame(scene, camera);
    std::memcpy(frame.mapped, &values, sizeof values);
    uint32_t draws = 0;
    for (const Effect& effect : effects) {
        if (!effectShown(shown, effect.index)) continue;
        drawBuiltTriangles(cmd, program, frame, effect.output, effect.counters, scene.output.fps,
                           effect.kind.look, effect.style);
        ++draws;
    }
    return draws;
}

// Transfers (counter resets, fills) made visible to the compute stages that follow.
void transferToComputeBarrier(VkCommandBuffer cmd);
// One compute stage's writes made visible to the next.
void computeToComputeBarrier(VkCommandBuffer cmd);
// The built geometry and indirect arguments made visible to the draws, copies and the host.
void computeToDrawBarrier(VkCommandBuffer cmd);

// Which scene frames a per-frame history has seen. A frame that does not follow the last one
// recorded of the same simulation (the first, a jump, a restarted simulation) starts it again.
class FrameHistory {
public:
    enum class Step {
        Same,    // the frame recorded last, again: the history stays as it is
        Next,    // the frame after it: the history advances
        Restart, // anything else: the history starts again, with no motion
    };
    Step step(uint64_t simulationSerial, uint32_t frame);
    bool recorded() const { return recorded_; }

private:
    uint64_t serial_ = 0;
    uint32_t frame_ = 0;
    bool recorded_ = false;
};

} // namespace mfx::render
