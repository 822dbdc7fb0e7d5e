// The smoke pass: every smoke grid of a simulation ray-marched through its pigment volume and
// composited over the rendered picture, after the scene and effect passes: the march stops at the
// scene's depth, and smoke behind a surface fades out over `fadeDistance` (docs/architecture.md
// "Formulas"), so it meets the floor and the character softly.
//
// Per grid, all on the GPU (the CPU never waits for it):
// - pigmentBounds (shaders/render/pigment_bounds.comp) finds the box of cells that hold pigment;
//   the march covers only that box and the composite rasterises only its faces
//   (shaders/render/smoke.vert), so pixels whose ray misses the pigment cost next to nothing and
//   an empty grid draws nothing;
// - the light's transmittance (shaders/render/light_transmittance.comp) is marched once over the
//   box, for the march to fetch;
// - the march (shaders/render/smoke_march.glsl: a compute pass on a GPU, a fragment pass over the
//   box's faces on a CPU device; SmokeMarch) writes the smoke's premultiplied colour and the scene
//   distance it marched to into a fluid buffer, at half the picture's width and height by
//   default;
// - the composite (shaders/render/smoke_composite.frag) lays the fluid buffer over the picture
//   with a depth-aware upsample, so the smoke keeps the silhouettes of what is in front of it.
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/scene/kinds/smoke_effect.h"
#include "fluid/grid_solver.h"
#include "render/render_target.h"
#include "render/scene_camera.h"
#include "shaders/shared/smoke_draw.h"
#include "sim/scene_simulation.h"

#include <array>
#include <map>
#include <optional>
#include <span>
#include <tuple>
#include <vector>

namespace mfx::render {

// How finely the smoke is marched: the fluid buffer's width and height against the picture's.
enum class SmokeResolution {
    Full, // one ray per pixel
    Half, // one ray per 2x2 pixels, about a quarter of the cost, upsampled by depth
};

// Which shader marches the rays (shaders/render/smoke_march.glsl).
enum class SmokeMarch {
    Auto,     // by device: Fragment on a CPU device, Compute on a GPU
    Fragment, // smoke.frag over the box's faces: only the texels whose ray meets the box run
    Compute,  // smoke_march.comp over the whole fluid buffer: on NVIDIA's H200, whose rasteriser
              // is a small part of the chip, several times faster; on lavapipe slower
};

struct SmokeLook {
    float densityScale = 8.0f; // optical density per unit of pigment alpha, per world unit
    float fadeDistance = 0.1f; // b, world units
    float stepsPerCell = 1.0f;
    // Cells whose pigment alpha is at most this count as empty: the march covers only the box of
    // the others. Higher shrinks the box (faster) and drops more of the thin smoke at its rim; at
    // 1e-4 and the default density, all the cells left out together make at most about half an
    // 8-bit level of opacity (0.2 %) on a ray 2.5 world units long.
    float pigmentThreshold = 1e-4f;
    SmokeResolution resolution = SmokeResolution::Half;
    SmokeMarch march = SmokeMarch::Auto;
    // The key light's transmittance volume: a texel a cell of the pigment's box, at most this many
    // a side (a wider box shares texels between cells).
    uint32_t maxLightCells = 128;
};

// The smoke lit otherwise than by the scene (a flipbook's six-way light maps, render/
// bake_renderer.h): this key light in place of the scene's first, and the effects' glow scaled.
struct SmokeRelight {
    scene::LightSpec key;
    float glowScale = 1.0f;
};

class SmokePass {
public:
    explicit SmokePass(const gpu::Context& ctx);

    // Records the composite of every grid of `simulation` into `target`'s single-sampled colour
    // (outside any rendering; after the scene's rendering has ended, so its depth is resolved).
    // With `shown` non-empty, a grid is drawn only while one of its effects' entries (by index in
    // scene.effects) is non-zero. Returns the number of grids drawn (a grid without pigment counts,
    // though nothing of it reaches the picture). With `relight`, lit as it says.
    //
    // The pass keeps one fluid buffer for the target's size and the look's resolution; a draw with
    // another size or resolution replaces it, so no earlier draw may still be executing then.
    uint32_t draw(VkCommandBuffer cmd, RenderTarget& target, const sim::SceneSimulation& simulation,
                  const SceneCamera& camera, std::span<const uint8_t> shown = {},
                  const SmokeLook& look = {}, const SmokeRelight* relight = nullptr);

    // One pigment volume (fluid/grid_solver.h: a solver's image, or the sparse domain's brick
    // atlas over its virtual domain) of `shape` whose low corner is at `origin`, shaded as
    // `shading` says (its grid's first smoke effect's). Over a brick atlas the bounds search runs
    // over the active bricks and the march skips the empty ones (shaders/render/smoke_march.glsl).
    struct Volume {
        fluid::PigmentVolume pigment;
        fluid::GridShape shape;
        glm::vec3 origin{0.0f};
        scene::SmokeShading shading;
        float time = 0.0f; // scene seconds (the cartoon look's billows boil with it)
    };
    void draw(VkCommandBuffer cmd, RenderTarget& target, std::span<const Volume> volumes,
              const SceneCamera& camera, const scene::LightSpec& key, const SmokeLook& look = {});

private:
    // The march and composite programs for one fluid buffer divisor (1 or 2), each march made
    // when first used: [compute][sparse][cartoon] (SmokeMarch; the sparse atlas's variant; the
    // cartoon look's surface march, composited by its own program).
    struct Programs {
        std::optional<gpu::Program> march[2][2][2];
        gpu::Program composite;
        std::optional<gpu::Program> cartoonComposite;
    };
    // The smoke's premultiplied colour and the scene distance its march used.
    struct FluidBuffer {
        gpu::Image color, distance;
        uint32_t divisor = 0;
        uint32_t targetWidth = 0, targetHeight = 0;
    };

    Programs& programsFor(uint32_t divisor);
    bool computeMarch(const SmokeLook& look) const;
    gpu::Program& marchProgram(Programs& programs, uint32_t divisor, bool compute, bool sparse,
                               bool cartoon);
    gpu::Program& cartoonComposite(Programs& programs, uint32_t divisor);
    static bool cartoon(const Volume& v) { return v.shading.preset == scene::SmokePreset::Cartoon; }
    // Volume i's march into the fluid buffer, by `programs` (those of `divisor`).
    void march(VkCommandBuffer cmd, RenderTarget& target, size_t i, const Volume& volume,
               const shared::SmokeDraw& draw, Programs& programs, uint32_t divisor, bool compute);
    void prepareFluidBuffer(const RenderTarget& target, uint32_t divisor);
    void findPigmentBounds(VkCommandBuffer cmd, std::span<const Volume> volumes,
                           const SmokeLook& look);
    // The key light's transmittance through volume i over its pigment's box, at its grid's
    // resolution (shaders/render/light_transmittance.comp), after its bounds, for its march.
    // The compute program in `slot`, made on first use (the sparse atlas's variants).
    gpu::Program& madeOnce(std::optional<gpu::Program>& slot, const char* name,
                           std::span<const uint32_t> spirv, uint32_t pushConstantSize);
    void marchLight(VkCommandBuffer cmd, size_t i, const Volume& volume,
                    const shared::SmokeDraw& draw, uint32_t maxCells);

    const gpu::Context& ctx_;
    gpu::Program& boundsFor(const gpu::Image& pigment) {
        return boundsPrograms_[pigment.format == VK_FORMAT_R16G16B16A16_SFLOAT ? 1 : 0];
    }
    std::array<gpu::Program, 2> boundsPrograms_; // for rgba32f and rgba16f pigment
    std::optional<gpu::Program> sparseBounds_;   // for a sparse atlas, made when first used
    gpu::Program light_;                         // light_transmittance for a pigment image
    std::optional<gpu::Program> sparseLight_;    // ... for a sparse atlas, made when first used
    std::map<uint32_t, Programs> programs_;      // by divisor, made when first used
    gpu::UniqueSampler volumeSampler_, nearestSampler_;
    gpu::UniqueSampler edgeSampler_; // linear, clamped to the edge: the light's transmittance
    FluidBuffer fluid_;
    std::vector<gpu::Buffer> bounds_; // shared::PigmentBounds of the i-th volume of a draw
    std::vector<gpu::Buffer> styles_; // shared::SmokeStyle of the i-th volume of a draw
    std::vector<gpu::Image> lights_;  // the light's transmittance of the i-th volume (r32f)
};

} // namespace mfx::render
