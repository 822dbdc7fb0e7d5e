#include "core/scene/effect_source.h"

namespace mfx::scene {

Result<trajectory::Source> effectSource(const anim::Character& character, const EffectSpec& e,
                                        trajectory::SurfaceReport* surface) {
    trajectory::Selection selection;
    selection.meshes = e.meshes;
    selection.bones = e.bones;
    selection.minBoneWeight = e.minBoneWeight;
    if (const std::optional<float> step = e.kind().surfaceSampling())
        return trajectory::selectSurfaceSource(character, selection, *step, surface);
    return trajectory::selectSource(character, selection);
}

} // namespace mfx::scene
