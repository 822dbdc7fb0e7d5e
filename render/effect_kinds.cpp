// The registry of effect passes (render/effect_kind_pass.h): every pass of render/kinds, which the
// build lists (render/effect_pass_list.h, generated), in the draw order each declares.
#include "render/effect_kind_pass.h"
#include "render/effect_pass_list.h" // generated: every pass of render/kinds
#include "sim/scene_simulation.h"

#include <algorithm>
#include <type_traits>

namespace mfx::render {

namespace {

// A pass made from the simulation's scene and cast, or from nothing of the simulation where
// its constructor takes neither.
template <class Pass>
std::unique_ptr<EffectKindPass> make(const gpu::Context& ctx,
                                     const sim::SceneSimulation& simulation,
                                     VkSampleCountFlagBits samples) {
    if constexpr (std::is_constructible_v<Pass, const gpu::Context&, VkSampleCountFlagBits>)
        return std::make_unique<Pass>(ctx, samples);
    else
        return std::make_unique<Pass>(ctx, simulation.scene(), simulation.cast(), samples);
}

template <class Pass>
EffectPassKind entry() {
    static_assert(std::is_base_of_v<EffectKindPass, Pass>);
    return {Pass::kPassName, Pass::kDrawOrder, Pass::drawnTypes(), make<Pass>};
}

template <class... Passes>
std::vector<EffectPassKind> sortedKinds(EffectPassList<Passes...>) {
    std::vector<EffectPassKind> kinds = {entry<Passes>()...};
    std::stable_sort(
        kinds.begin(), kinds.end(),
        [](const EffectPassKind& a, const EffectPassKind& b) { return a.drawOrder < b.drawOrder; });
    return kinds;
}

} // namespace

std::span<const EffectPassKind> effectPassKinds() {
    static const std::vector<EffectPassKind> kinds = sortedKinds(EffectPassTypes{});
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
