// The silhouette-of-motion blur shell of deforming meshes, on the GPU: Jones 2004, "Geometric
// Motion Blur for Deforming Polygonal Models" (Sec. 3.2.2, the parameters and averaged normals;
// 3.2.3, the per-polygon ring; 3.2.4, finding the silhouette of motion; 3.2.5, the quad strips;
// 3.3, holes and popping). For each silhouette_shell effect of the scene:
//   * its bound vertices (bones, meshes) are skinned for the frame (anim::SkinVertices) and given
//     normals averaged over their polygons (silhouette_shell_normals.comp);
//   * the silhouette of motion is updated `updatesPerFrame` times between two recorded frames, or
//     once every `framesPerUpdate` frames (ShellCadence), each polygon recording its edge on it, or
//     its last such edge, in its ring of past edges (silhouette_shell_update.comp);
//   * each polygon that had an edge on the silhouette within the fade-out count draws a quad strip
//     from its edge on the live mesh back through its ring, alpha falling linearly from the
//     initial value to 0, the whole strip fading while the polygon is off the silhouette
//     (silhouette_shell_build.comp);
//   * it is drawn in the effects pass by one indirect draw with the blur volume's shaders (lit,
//     translucent triangles): nothing is read back to the CPU.
// The rings advance only when a scene frame is recorded (FrameRenderer::record); a frame that does
// not follow the last one recorded starts them again: no motion, no shell.
#pragma once

#include "core/anim/character.h"
#include "core/anim/skin_vertices.h"
#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/scene/kinds/silhouette_shell_effect.h"
#include "core/scene/scene.h"
#include "core/trajectory/trajectory_source.h"
#include "render/effect_geometry.h"
#include "render/effect_kind_pass.h"
#include "render/mesh_effect_pass.h"
#include "render/scene_camera.h"
#include "shaders/shared/silhouette_shell.h"
#include "shaders/shared/trajectory.h"

#include <cstdint>
#include <span>
#include <vector>

namespace mfx::sim {
class SceneSimulation;
}

namespace mfx::render {

// When the silhouette of motion is updated: blur time / subdivisions apart (Jones 2004, Sec.
// 3.2.2), rounded to a whole number of updates a recorded frame (at most
// MFX_SHELL_MAX_UPDATES_PER_FRAME) or, when that is longer than a frame, to one update every whole
// number of frames. Without a blur time: one update a frame.
struct ShellCadence {
    uint32_t updatesPerFrame = 1; // updates between two recorded frames that have an update
    uint32_t framesPerUpdate = 1; // recorded frames from one update to the next
};

// One effect of the pass (render/mesh_effect_pass.h).
struct SilhouetteShellEffect : MeshEffect {
    SilhouetteShellEffect(MeshEffect common, const scene::SilhouetteShellSpec& settings)
        : MeshEffect(std::move(common)), kind(settings) {}
    scene::SilhouetteShellSpec kind;
    uint32_t triangleCount = 0, historySlots = 2;
    ShellCadence cadence;
    uint32_t framesSinceUpdate = 0; // recorded frames since the last update (or start)
    bool updated = false;           // whether the last recorded frame updated
    gpu::Buffer adjacency, triangles, current, last, states, history;
    uint32_t newest = 0;
};

class SilhouetteShellPass : public MeshEffectPass<SilhouetteShellEffect> {
public:
    static constexpr const char* kPassName = "silhouette_shell";
    static constexpr int kDrawOrder = 30;

    // The scene's silhouette_shell effects, each on the character of the cast it follows (the cast
    // must outlive the pass), drawn into targets of `samples` samples. Effects whose selection
    // leaves no triangle are left out.
    SilhouetteShellPass(const gpu::Context& ctx, const scene::Scene& scene,
                        std::span<const anim::Character> cast,
                        VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);

    // After the recording has finished executing, what effect `effect` (its index in
    // scene.effects) built: all zero for an effect that is not a silhouette_shell.
    struct Counts {
        uint32_t vertices = 0;            // triangle vertices drawn, 6 a quad
        uint32_t silhouetteTriangles = 0; // polygons with an edge on this frame's last silhouette
                                          // (0 on a frame without an update)
        uint32_t strips = 0;              // quad strips drawn
        uint32_t fadingStrips = 0;        // of them, polygons off the silhouette fading out
        uint32_t updatesPerFrame = 0;     // silhouette updates on a frame that has them
        uint32_t framesPerUpdate = 0;     // recorded frames from one update to the next
        bool updated = false;             // whether this frame updated the silhouette
    };
    Counts counts(size_t effect) const;
    // The triangles of effect `effect` as drawn: each strip's quads (6 vertices each, from the
    // live mesh back; the first quad's vertices 0 and 1 are the live edge, 2 and 5 the next pair),
    // strips in no fixed order. position.w is the place along the strip, pair k at
    // k / subdivisions. Reads back; waits.
    std::vector<shared::TrajectoryVertex> geometry(size_t effect) const;
    // This frame's skinned positions of effect `effect`'s bound vertices (the live mesh). Reads
    // back; waits.
    std::vector<glm::vec3> livePositions(size_t effect) const;

private:
    void recordEffect(VkCommandBuffer cmd, const sim::SceneSimulation& simulation, uint32_t frame,
                      Effect& effect, bool reset) override;
    gpu::Program normals_, update_, build_;
};

// The polygons around each vertex as silhouette_shell_normals.comp reads them: vertexCount + 1
// offsets, then the triangle lists they index. Vertices at the same bind-pose position count as
// one, so a flat-shaded mesh (every polygon its own vertex copies) still gets normals averaged over
// all the polygons that meet at a point (Jones 2004, Sec. 3.2.2).
std::vector<uint32_t> shellVertexTriangles(const std::vector<shared::SkinVertexIn>& vertices,
                                           const std::vector<uint32_t>& triangles);

// The cadence of `shell` at `fps` recorded frames a second.
ShellCadence shellCadence(const scene::SilhouetteShellSpec& shell, float fps);

} // namespace mfx::render
