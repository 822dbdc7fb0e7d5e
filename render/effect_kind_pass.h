// What every effect pass of a frame is (docs/architecture.md, "Adding an effect kind"): the frame
// holds a list of them, built from the scene by the registry below, and records each the same way:
// advance() once per new simulation frame (its history and compute work, before any drawing),
// then draw() inside the frame's rendering (the scene's colour and depth, depth test on,
// premultiplied alpha), returning the number of draws. Passes whose history only the simulation
// keeps (the trajectory effects) leave advance() empty.
#pragma once

#include "render/scene_camera.h"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

namespace mfx::gpu {
class Context;
struct Image;
} // namespace mfx::gpu
namespace mfx::sim {
class SceneSimulation;
}

namespace mfx::render {

class EffectKindPass {
public:
    virtual ~EffectKindPass() = default;

    // Records frame `frame` of `simulation` (its pose is the frame's: after recordFrame). The
    // previous recording must have finished executing.
    virtual void advance(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                         uint32_t frame) = 0;
    // Records the draws of what the pass holds at scene time `time` (inside rendering). With
    // `shown` non-empty, only effects whose entry (index in scene.effects) is non-zero.
    virtual uint32_t draw(VkCommandBuffer cmd, const sim::SceneSimulation& simulation,
                          const SceneCamera& camera, float time,
                          std::span<const uint8_t> shown = {}) = 0;
    // The scene's depth (single-sampled, shader-read-only while the effects draw) that soft
    // effects fade against (shaders/render/depth_fade.glsl), or null: none this frame.
    void setFadeDepth(const gpu::Image* depth) { fadeDepth_ = depth; }
    // The frame's camera (the renderer's, which outlives the pass), for the work advance() does
    // from the eye's point of view (the swept volume's silhouette edges); null: the scene's camera.
    void setCamera(const SceneCamera* camera) { camera_ = camera; }

protected:
    const gpu::Image* fadeDepth_ = nullptr;
    const SceneCamera* camera_ = nullptr;
};

// One registered kind of pass: the effect types it draws (scene "type" names) and how to make it
// for a simulation's scene and cast, drawing into targets of `samples` samples.
struct EffectPassKind {
    const char* name;
    int drawOrder;
    std::vector<std::string> types;
    std::unique_ptr<EffectKindPass> (*make)(const gpu::Context& ctx,
                                            const sim::SceneSimulation& simulation,
                                            VkSampleCountFlagBits samples);
};

// The registered passes are the files render/kinds/<name>_pass.h, found by the build
// (render/CMakeLists.txt lists them as EffectPassList<...>). Each declares the class
// mfx::render::<Name>Pass, deriving from EffectKindPass, with
//   static constexpr const char* kPassName;  // for tables and errors
//   static constexpr int kDrawOrder;         // passes draw in increasing order
//   static std::vector<std::string> drawnTypes(); // the scene effect types it draws
// and a constructor (ctx, scene, cast, samples) (the cast: std::span<const anim::Character>, one
// per scene.characters entry) or, for a pass that needs neither the scene nor the cast,
// (ctx, samples).
template <class... Passes>
struct EffectPassList {};

// Every kind, in draw order (render/effect_kinds.cpp).
std::span<const EffectPassKind> effectPassKinds();

// The passes the simulation's scene calls for (a kind none of whose types the scene has is not
// made), in draw order.
std::vector<std::unique_ptr<EffectKindPass>>
makeEffectPasses(const gpu::Context& ctx, const sim::SceneSimulation& simulation,
                 VkSampleCountFlagBits samples);

} // namespace mfx::render
