// Speed-lines (motion lines; Xu et al., Sec. 4.2): each line piece of the effect's trajectory
// queue widened into a ribbon (camera- or blade-facing) or a tube by the geometry stage, tapering
// along the segment and with age or by its width over life, with a white-hot core
// (shaders/render/effect_lines.*; render/trail_effect_pass.h).
//
// Each new frame, advance() finds the direction of every live sample along its line, shared by the
// pieces that meet there within a segment and across the weld between two frames' segments
// (shaders/render/ribbon_joins.comp): the ribbon's edges then run as one curve instead of each
// piece, and each frame's segment, ending across its own direction.
//
// A sheet (scene "shape": "sheet") is drawn instead as one surface between its two lines
// (shaders/render/effect_sheet.vert), each piece of the pair two triangles: its edges are the
// lines themselves.
//
// A ribbon or sheet with a texture (scene::RibbonTexture) binds it at binding 5, loaded from the
// scene's folder when first drawn (core/scene/ribbon_texture.h); one tiled by distance also keeps,
// with each queue, every ring vertex's distance along its line (binding 4): advance() finds those
// of the segments written since the last frame, each from its predecessor's
// (shaders/render/ribbon_distance.comp), so the pattern stays where it was drawn while the trail
// grows and ages.
#pragma once

#include "core/scene/kinds/trail_effects.h"
#include "render/trail_effect_pass.h"

#include <map>

namespace mfx::render {

class SpeedLinesPass : public TrailEffectPass {
public:
    // Registry (render/effect_kind_pass.h): after the blur volumes, before the particles.
    static constexpr const char* kPassName = "speed-lines";
    static constexpr int kDrawOrder = 41;
    static std::vector<std::string> drawnTypes() { return {scene::SpeedLinesSpec::kType}; }

    explicit SpeedLinesPass(const gpu::Context& ctx,
                            VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);

    // Records the joins of every speed-line effect's live segments (after the simulation recorded
    // `frame`).
    void advance(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                 uint32_t frame) override;

private:
    gpu::Buffer makeStyle(const scene::EffectSpec& spec) const override;
    std::vector<gpu::DescriptorWrite> extraBindings(const sim::SceneSimulation& simulation,
                                                    const TrajectoryEffect& effect) override;
    void setLook(shared::EffectDraw& draw, const TrajectoryEffect& effect) const override;
    DrawSource drawSource(const TrajectoryEffect& effect) override;
    static bool isSheet(const TrajectoryEffect& effect);
    static const scene::RibbonTexture& textureOf(const TrajectoryEffect& effect);
    static bool tiledByDistance(const TrajectoryEffect& effect);
    // Records the joins of the effect's live segments; false when it has none.
    bool advanceJoins(VkCommandBuffer cmd, const TrajectoryEffect& effect);
    // Records the distances of the queue's segments written since they were last found; false
    // when there were none.
    bool advanceDistances(VkCommandBuffer cmd, const TrajectoryEffect& effect,
                          uint64_t simulationSerial);
    // Bindings 4 and 5: the effect's distances and texture (or stand-ins never read).
    std::vector<gpu::DescriptorWrite> textureBindings(const sim::SceneSimulation& simulation,
                                                      const TrajectoryEffect& effect);

    // An effect's joins: the direction at each ring vertex, the chain of live segments it was
    // found for (host-visible), and the queue's frames recorded then (a draw uses the joins only
    // while the queue has recorded nothing since; 0: never found).
    struct Joins {
        gpu::Buffer directions, chain;
        uint64_t framesRecorded = 0;
    };
    const Joins* joinsFor(const TrajectoryEffect& effect) const;

    // A queue's distances along its lines (by ring vertex), and which frame's segment each slot's
    // distances were found for (frame + 1; 0: none). The simulation they belong to, by serial
    // (another simulation's queue may come to the same address).
    struct Distances {
        gpu::Buffer values, segments;
        std::vector<uint64_t> slotFrame;
        uint64_t simulation = 0;
    };

    FadeDepthSource fadeDepthSource_;
    RibbonTextureSource textureSource_;
    gpu::Program joinsProgram_, distanceProgram_, sheet_;
    // A sheet's triangles for one segment of S pieces, by S (host-visible index buffers).
    std::map<uint32_t, gpu::Buffer> sheetIndices_;
    gpu::Buffer none_; // bound at binding 3 for an effect without joins (never read)
    std::map<const trajectory::Queue*, Joins> joins_;
    std::map<const trajectory::Queue*, Distances> distances_;
    // The textures, by file (made when first drawn; no image: it could not be loaded).
    std::map<std::string, gpu::Image> textures_;
};

} // namespace mfx::render
