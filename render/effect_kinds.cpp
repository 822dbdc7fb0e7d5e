// The registry of effect passes (render/effect_kind_pass.h). Adding a kind of effect pass means
// one line here; the order of the lines is the order they draw in.
#include "core/scene/kinds/afterimage_effect.h"
#include "core/scene/kinds/silhouette_shell_effect.h"
#include "core/scene/kinds/swept_volume_effect.h"
#include "core/scene/kinds/trail_effects.h"
#include "core/scene/scene.h"
#include "render/afterimage_pass.h"
#include "render/effect_kind_pass.h"
#include "render/effect_pass.h"
#include "render/silhouette_shell_pass.h"
#include "render/swept_volume_pass.h"
#include "sim/scene_simulation.h"

#include <algorithm>

namespace mfx::render {

namespace {

// A pass made from the simulation's scene and character.
template <class Pass>
std::unique_ptr<EffectKindPass> make(const gpu::Context& ctx,
                                     const sim::SceneSimulation& simulation,
                                     VkSampleCountFlagBits samples) {
    return std::make_unique<Pass>(ctx, simulation.scene(), simulation.character(), samples);
}
// The trajectory effects' pass draws the simulation's queues: it needs nothing of the scene.
template <>
std::unique_ptr<EffectKindPass> make<EffectPass>(const gpu::Context& ctx,
                                                 const sim::SceneSimulation&,
                                                 VkSampleCountFlagBits samples) {
    return std::make_unique<EffectPass>(ctx, samples);
}

} // namespace

std::span<const EffectPassKind> effectPassKinds() {
    static const EffectPassKind kinds[] = {
        // The smear first: by default an opaque copy of the mesh, it writes depth.
        {"afterimage", {scene::AfterimageSpec::kType}, make<AfterimagePass>},
        {"swept_volume", {scene::SweptVolumeSpec::kType}, make<SweptVolumePass>},
        {"silhouette_shell", {scene::SilhouetteShellSpec::kType}, make<SilhouetteShellPass>},
        // Blur volumes, then speed-lines, then particles: the thin effects stay on top.
        {"trajectory",
         {scene::MotionBlurSpec::kType, scene::SpeedLinesSpec::kType,
          scene::MotionParticlesSpec::kType},
         make<EffectPass>},
    };
    return kinds;
}

std::vector<std::unique_ptr<EffectKindPass>>
makeEffectPasses(const gpu::Context& ctx, const sim::SceneSimulation& simulation,
                 VkSampleCountFlagBits samples) {
    std::vector<std::unique_ptr<EffectKindPass>> passes;
    for (const EffectPassKind& kind : effectPassKinds()) {
        const bool used =
            std::any_of(simulation.scene().effects.begin(), simulation.scene().effects.end(),
                        [&](const scene::EffectSpec& e) {
                            return std::find(kind.types.begin(), kind.types.end(),
                                             std::string(e.type())) != kind.types.end();
                        });
        if (used) passes.push_back(kind.make(ctx, simulation, samples));
    }
    return passes;
}

} // namespace mfx::render
