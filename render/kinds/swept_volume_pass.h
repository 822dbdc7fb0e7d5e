// The swept-volume motion blur of rigid parts, on the GPU: Wloka and Zeleznik 1996, "Interactive
// Real-Time Motion Blur" (Sec. 3, one segment; 3.4, transparency as a temporal filter; 4.2, n
// segments along a curved path; 4.3, rotation). For each swept_volume effect of the scene:
//   * its bound vertices (bones, meshes) are skinned for the frame (anim::SkinVertices) and their
//     positions written into a ring of the last n + 1 recorded positions
//     (swept_volume_record.comp);
//   * the part's motion vector over the sweep, its path length and its extent along the motion
//     give the trailing transparency (swept_volume_motion.comp, one workgroup);
//   * the part is split by its triangles' normals against the motion into the side facing it
//     (leading) and the side facing away (trailing); the trailing side is drawn where it was n
//     frames ago and the contour-line edges between the two are swept back through the recorded
//     positions by quads whose alpha falls from opaque to the trailing value, shaped by the
//     temporal filter (swept_volume_build.comp);
//   * it is drawn in the effects pass by one indirect draw with the blur volume's shaders (lit,
//     translucent triangles): nothing is read back to the CPU.
// The ring advances only when a scene frame is recorded (FrameRenderer::record); a frame that does
// not follow the last one recorded starts it again: no motion, no volume.
#pragma once

#include "core/anim/character.h"
#include "core/anim/skin_vertices.h"
#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/scene/kinds/swept_volume_effect.h"
#include "core/scene/scene.h"
#include "core/trajectory/trajectory_source.h"
#include "render/effect_geometry.h"
#include "render/effect_kind_pass.h"
#include "render/mesh_effect_pass.h"
#include "render/scene_camera.h"
#include "shaders/shared/swept_volume.h"
#include "shaders/shared/trajectory.h"

#include <cstdint>
#include <span>
#include <vector>

namespace mfx::sim {
class SceneSimulation;
}

namespace mfx::render {

// One effect of the pass (render/mesh_effect_pass.h).
struct SweptVolumeEffect : MeshEffect {
    SweptVolumeEffect(MeshEffect common, const scene::SweptVolumeSpec& settings)
        : MeshEffect(std::move(common)), kind(settings) {}
    scene::SweptVolumeSpec kind;
    uint32_t triangleCount = 0, edgeCount = 0, historySlots = 2;
    gpu::Buffer history, triangles, edges;
    uint32_t newest = 0, filled = 0;
};

class SweptVolumePass : public MeshEffectPass<SweptVolumeEffect> {
public:
    static constexpr const char* kPassName = "swept_volume";
    static constexpr int kDrawOrder = 20;

    // The scene's swept_volume effects, each on the character of the cast it follows (the cast must
    // outlive the pass), drawn into targets of `samples` samples. Effects whose selection leaves no
    // vertex are left out (the simulation refuses such scenes first).
    SweptVolumePass(const gpu::Context& ctx, const scene::Scene& scene,
                    std::span<const anim::Character> cast,
                    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);

    // After the recording has finished executing, what effect `effect` (its index in
    // scene.effects) built: all zero for an effect that is not a swept_volume.
    struct Counts {
        uint32_t vertices = 0;          // translucent triangle vertices drawn, 3 a triangle
        uint32_t contourEdges = 0;      // contour-line edges joined
        uint32_t trailingTriangles = 0; // back triangles drawn at the oldest position
        glm::vec3 motion{0.0f};         // the part's motion over the sweep (world units)
        float pathLength = 0.0f;        // the length of its path through the samples
        float extent = 0.0f;            // its extent along the motion
        float trailingAlpha = 0.0f;     // the alpha of the trailing side
    };
    Counts counts(size_t effect) const;
    // The triangles of effect `effect` as drawn, three vertices a triangle: each contour-line
    // edge's quads (6 vertices each, segments × sub_samples of them, in order from now back),
    // then the trailing triangles, in no fixed order between edges. position.w is the place along
    // the sweep, 0 now and 1 at the oldest sample. Reads back; waits.
    std::vector<shared::TrajectoryVertex> geometry(size_t effect) const;

private:
    void recordEffect(VkCommandBuffer cmd, const sim::SceneSimulation& simulation, uint32_t frame,
                      Effect& effect, bool reset) override;
    gpu::Program record_, motion_, build_;
};

// The interior edges of a triangle list as swept_volume_build.comp reads them, 6 words an edge:
// the two triangles beside it, the edge's vertices as the first indexes them, then as the second.
// Vertices at the same bind-pose position count as one, so a mesh split at its seams (hard edges,
// UV seams) still has its contour (Wloka and Zeleznik 1996, Sec. 3.2: an edge between a front and
// a back polygon). Edges with one triangle, or more than two, are left out.
std::vector<uint32_t> sweptVolumeEdges(const std::vector<shared::SkinVertexIn>& vertices,
                                       const std::vector<uint32_t>& triangles);

} // namespace mfx::render
