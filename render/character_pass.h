// The scene pass: the scene's characters, each skinned on the GPU every frame (anim::SkinVertices,
// dual quaternion skinning from a palette per skin), and the stage (a floor and a backdrop), lit
// with the scene's key light; each character in its style (scene::characterStyle: lit, or toon with
// a banded ramp, a rim light and an inverted-hull outline). Recording is in two parts: skin()
// before rendering begins (compute), then draw() and drawOutline() inside it.
//
// Why an inverted hull for the outline rather than an edge pass over depth and normals: it is one
// more draw of the character's own triangles (a fraction of a full-screen pass on a CPU
// rasteriser), it outlines the character alone (not the stage or the effects), multisampling
// smooths it like any geometry, and its width is set in pixels by the vertex shader.
#pragma once

#include "core/anim/character.h"
#include "core/anim/sampling.h"
#include "core/anim/skin_vertices.h"
#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/scene/scene.h"
#include "render/scene_camera.h"

#include <memory>
#include <span>
#include <vector>

namespace mfx::render {

class CharacterPass {
public:
    // The cast (one character per scene.characters entry) must outlive the pass.
    CharacterPass(const gpu::Context& ctx, std::span<const anim::Character> cast,
                  const scene::Scene& scene, VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);
    CharacterPass(const gpu::Context& ctx, const anim::Character& character,
                  const scene::Scene& scene, VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT)
        : CharacterPass(ctx, std::span<const anim::Character>(&character, 1), scene, samples) {}

    // Records the skinning of every primitive, character c in `poses[c]` placed by
    // `placements[c]`. The palettes are written now: the previous recording must have finished
    // executing.
    void skin(VkCommandBuffer cmd, std::span<const anim::Pose> poses,
              std::span<const glm::mat4> placements);
    // The same for a pass of one character.
    void skin(VkCommandBuffer cmd, const anim::Pose& pose, const glm::mat4& placement) {
        skin(cmd, std::span<const anim::Pose>(&pose, 1), std::span<const glm::mat4>(&placement, 1));
    }
    // Records the key light's shadow map of the skinned character (outside any rendering; after
    // skin()). Without it, or for a light with "shadow": false, nothing is shadowed.
    void shadow(VkCommandBuffer cmd);
    // Records the draws (inside rendering to a colour + depth target of
    // kSceneColorFormat/kDepthFormat): the stage, unless `withStage` is false, and the character.
    void draw(VkCommandBuffer cmd, const SceneCamera& camera, bool withStage = true);
    // Whether a character has an outline (toon, width > 0), and the draws of the outlines (after
    // draw(), in the same rendering, into a target of `width` x `height` pixels).
    bool hasOutline() const { return outlined_; }
    void drawOutline(VkCommandBuffer cmd, uint32_t width, uint32_t height);

    static constexpr uint32_t kShadowSize = 2048;

private:
    struct Part {
        const anim::Primitive* primitive = nullptr;
        gpu::Buffer input, output, indices, palette;
        gpu::Buffer outlineInput, outlineOutput; // the bind pose with welded normals, skinned
        uint32_t vertexCount = 0, indexCount = 0, jointCount = 0;
        size_t character = 0; // its cast member
        bool outlined = false;
    };
    struct StageMesh {
        gpu::Buffer vertices, indices;
        uint32_t indexCount = 0;
        glm::vec3 colour{1.0f};
    };
    void addCharacter(const gpu::Context& ctx, size_t c, bool outlined);
    void addStageQuad(const gpu::Context& ctx, glm::vec3 centre, glm::vec3 u, glm::vec3 v,
                      glm::vec3 colour);

    const gpu::Context& ctx_;
    std::span<const anim::Character> cast_;
    const scene::Scene scene_; // a copy: the pass may outlive the simulation that owned it
    anim::SkinVertices skinning_;
    gpu::Program program_, shadowProgram_, outlineProgram_;
    bool outlined_ = false;
    gpu::Buffer frame_;
    gpu::Image shadowMap_;
    gpu::UniqueSampler shadowSampler_;
    glm::mat4 lightViewProjection_{1.0f};
    bool shadowReady_ = false;
    std::vector<gpu::DescriptorWrite> resources_; // the frame and the shadow map
    std::vector<Part> parts_;
    std::vector<StageMesh> stage_;
};

} // namespace mfx::render
