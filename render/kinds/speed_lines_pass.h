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
    std::vector<gpu::DescriptorWrite> extraBindings(const TrajectoryEffect& effect) const override;
    void setLook(shared::EffectDraw& draw, const TrajectoryEffect& effect) const override;
    DrawSource drawSource(const TrajectoryEffect& effect) override;
    static bool isSheet(const TrajectoryEffect& effect);

    // An effect's joins: the direction at each ring vertex, the chain of live segments it was
    // found for (host-visible), and the queue's frames recorded then (a draw uses the joins only
    // while the queue has recorded nothing since; 0: never found).
    struct Joins {
        gpu::Buffer directions, chain;
        uint64_t framesRecorded = 0;
    };
    const Joins* joinsFor(const TrajectoryEffect& effect) const;

    FadeDepthSource fadeDepthSource_;
    gpu::Program joinsProgram_, sheet_;
    // A sheet's triangles for one segment of S pieces, by S (host-visible index buffers).
    std::map<uint32_t, gpu::Buffer> sheetIndices_;
    gpu::Buffer none_; // bound at binding 3 for an effect without joins (never read)
    std::map<const trajectory::Queue*, Joins> joins_;
};

} // namespace mfx::render
