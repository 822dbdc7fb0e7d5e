#include "core/scene/effect_source.h"

namespace mfx::scene {

Result<trajectory::Source> effectSource(const anim::Character& character, const EffectSpec& e,
                                        trajectory::SurfaceReport* surface) {
    trajectory::Selection selection;
    selection.meshes = e.meshes;
    selection.bones = e.bones;
    selection.minBoneWeight = e.minBoneWeight;
    if (e.type == EffectType::Smoke && e.emission == Emission::Surface)
        return trajectory::selectSurfaceSource(character, selection, e.surfaceStep, surface);
    return trajectory::selectSource(character, selection);
}

} // namespace mfx::scene
