// The afterimage toon blur, on the GPU: Smith 2016, "Afterimage Toon Blur: Procedural Generation
// of Cartoon Blur for 3D Models in Real Time" (chapter 4, single afterimage; chapter 5,
// multi-afterimage). For each afterimage_smear effect of the scene:
//   * its bound vertices (bones, meshes) are skinned for the frame (anim::SkinVertices) and their
//     positions written into a ring of recorded positions, one slot per scene frame
//     (afterimage_record.comp);
//   * each vertex facing away from its motion is pushed back along it, by the strengths of the
//     character's travel and of the animation's own motion times a per-vertex random value that
//     depends on the vertex index alone (that of its first copy at the same bind-pose position),
//     with the taper and speed thresholds of Sec. 4.3 and 5.3 (afterimage_smear.comp);
//   * the copies of a seam vertex move together: each takes the push of its first pushed copy
//     (Sec. 5.4; afterimage_weld.comp);
//   * the drawn geometry is built (afterimage_build.comp): the smeared copy of the bound mesh
//     (its triangles with a pushed vertex), a speed-line from each pushed vertex to where it is
//     pushed, or arcs through the recorded positions (multi);
//   * it is drawn in the effects pass by indirect draws, with the effect shaders (lit triangles,
//     camera-facing ribbons): nothing is read back to the CPU.
// The ring advances only when a scene frame is recorded (FrameRenderer::record); redrawing a paused
// frame draws the same geometry. A frame that does not follow the last one recorded (the first,
// a jump, a new simulation) starts the ring again: no motion, no smear.
#pragma once

#include "core/anim/character.h"
#include "core/anim/skin_vertices.h"
#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/scene/kinds/afterimage_effect.h"
#include "core/scene/scene.h"
#include "core/trajectory/trajectory_source.h"
#include "render/effect_geometry.h"
#include "render/effect_kind_pass.h"
#include "render/mesh_effect_pass.h"
#include "render/scene_camera.h"
#include "shaders/shared/afterimage.h"
#include "shaders/shared/trajectory.h"

#include <cstdint>
#include <span>
#include <vector>

namespace mfx::sim {
class SceneSimulation;
}

namespace mfx::render {

// One effect of the pass (render/mesh_effect_pass.h).
struct AfterimageEffect : MeshEffect {
    AfterimageEffect(MeshEffect common, const scene::AfterimageSpec& settings)
        : MeshEffect(std::move(common)), kind(settings) {}
    scene::AfterimageSpec kind;
    uint32_t primitiveCount = 0, historySlots = 2, outputCapacity = 0;
    gpu::Buffer history, decided, copies, pushed, primitives, indices;
    std::vector<uint32_t> copyTable; // as uploaded to `copies`
    uint32_t newest = 0, filled = 0;
};

class AfterimagePass : public MeshEffectPass<AfterimageEffect> {
public:
    static constexpr const char* kPassName = "afterimage";
    // First: by default an opaque copy of the mesh, the smear writes depth.
    static constexpr int kDrawOrder = 10;

    // The scene's afterimage_smear effects, each on the character of the cast it follows (the cast
    // must outlive the pass), drawn into targets of `samples` samples. Effects whose selection
    // leaves no vertex are left out (the simulation refuses such scenes first).
    AfterimagePass(const gpu::Context& ctx, const scene::Scene& scene,
                   std::span<const anim::Character> cast,
                   VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);

    // EffectKindPass (render/mesh_effect_pass.h): it draws lines and arcs as well.
    uint32_t draw(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                  const SceneCamera& camera, float time,
                  std::span<const uint8_t> shown = {}) override;

    // After the recording has finished executing, what effect `effect` (its index in
    // scene.effects) built: all zero for an effect that is not an afterimage_smear.
    struct Counts {
        uint32_t pushedVertices = 0; // rear vertices pushed back this frame
        uint32_t triangles = 0;      // smear: triangles drawn
        uint32_t lineVertices = 0;   // speed lines (2 a line) or arcs (3 a triangle)
        float fastest = 0.0f;        // the fastest bound vertex's motion (world units per frame)
    };
    Counts counts(size_t effect) const;
    // The geometry of effect `effect` as drawn (smear: the vertices of its drawn triangles, three
    // a triangle; speed lines: two a line; multi: three a triangle). Reads back; waits.
    std::vector<shared::TrajectoryVertex> geometry(size_t effect) const;
    // Per bound vertex of effect `effect` after the frame: as afterimage_smear.comp decided it on
    // its own (`decided`) and as drawn once the copies of seam vertices agree (`drawn`),
    // position.w 1 where pushed back; `copies` as afterimageCopies gives them. Reads back; waits.
    struct Decisions {
        std::vector<shared::TrajectoryVertex> decided, drawn;
        std::vector<uint32_t> copies;
    };
    Decisions decisions(size_t effect) const;

private:
    void recordEffect(VkCommandBuffer cmd, const sim::SceneSimulation& simulation, uint32_t frame,
                      Effect& effect, bool reset) override;
    gpu::Program record_, smear_, weld_, build_;
    gpu::Program smearDraw_, lineDraw_, arcDraw_;
    FadeDepthSource fadeDepthSource_;
    RibbonTextureSource textureSource_; // the lines have no texture: stand-ins
    gpu::Buffer noJoins_; // the speed-line program's joins binding (unused by the afterimage)
    void beginFrame(const sim::SceneSimulation& simulation, bool reset) override;
    // Each character's root and its travel this frame (by cast member).
    std::vector<glm::vec3> lastRoots_, characterMotions_;
};

// The copies of each bound vertex at one bind-pose position, as afterimage_weld.comp reads them:
// vertexCount + 1 offsets into the result, then each vertex's group of copies (itself included)
// in index order.
std::vector<uint32_t> afterimageCopies(const std::vector<shared::SkinVertexIn>& vertices);

} // namespace mfx::render
