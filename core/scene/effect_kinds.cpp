#include "core/scene/effect_kinds.h"

#include "core/scene/effect_kind_headers.h" // generated: every header of core/scene/kinds
#include "core/scene/json_object.h"

namespace mfx::scene {

namespace {

template <class Kind>
EffectKindEntry entry() {
    return {Kind::kType, Kind::keys(), Kind::parse};
}

} // namespace

std::span<const EffectKindEntry> effectKinds() {
    static const std::vector<EffectKindEntry> kinds = {
        entry<SpeedLinesSpec>(),      // Xu et al., Sec. 4.2
        entry<MotionBlurSpec>(),      // Xu et al., Sec. 4.4
        entry<MotionParticlesSpec>(), // Xu et al., Sec. 4.3
        entry<SmokeSpec>(),           // Xu et al., Sec. 5
        entry<AfterimageSpec>(),      // Smith 2016
        entry<SweptVolumeSpec>(),     // Wloka and Zeleznik 1996
        entry<SilhouetteShellSpec>(), // Jones 2004
    };
    return kinds;
}

const std::vector<std::string>& commonEffectKeys() {
    static const std::vector<std::string> keys = {
        "type", "name", "bones", "meshes", "min_bone_weight", "start", "end"};
    return keys;
}

namespace detail {

EffectSpec readEffect(const Object& o, size_t index) {
    std::vector<std::string> types;
    for (const EffectKindEntry& kind : effectKinds())
        types.push_back(kind.type);
    if (!o.has("type")) {
        std::string listed;
        for (size_t i = 0; i < types.size(); ++i)
            listed += (i == 0 ? "" : i + 1 == types.size() ? " or " : ", ") + types[i];
        fail(o.at("type"), "missing; every effect needs a type: " + listed);
    }
    const std::string type = o.choice("type", "", types);
    const EffectKindEntry& kind =
        *std::find_if(effectKinds().begin(), effectKinds().end(),
                      [&](const EffectKindEntry& k) { return type == k.type; });

    std::vector<std::string> allowed = commonEffectKeys();
    allowed.insert(allowed.end(), kind.keys.begin(), kind.keys.end());
    std::vector<std::string> elsewhere; // keys of the other kinds
    for (const EffectKindEntry& other : effectKinds())
        for (const std::string& key : other.keys)
            if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
                elsewhere.push_back(key);
    o.onlyKeys(allowed, elsewhere, "not a key of " + type + " effects");

    // The common keys first (their errors come first), then the kind's own.
    std::string name = o.string("name", type + "#" + std::to_string(index));
    std::vector<std::string> bones = o.strings("bones");
    std::vector<std::string> meshes = o.strings("meshes");
    const float minBoneWeight = float(o.number("min_bone_weight", 0.5, 0.0, 1.0, true));
    const float start = float(o.number("start", 0.0, 0.0, 1e5));
    const std::optional<float> end = o.optionalNumber("end", 0.0, 1e5);
    if (end && *end <= start)
        fail(o.at("end"), formatNumber(*end) + " is not after start (" + formatNumber(start) + ")");

    EffectSpec e(kind.parse(o));
    e.name = std::move(name);
    e.bones = std::move(bones);
    e.meshes = std::move(meshes);
    e.automaticBones = !o.has("bones") && !o.has("meshes");
    e.automaticStride = !o.has("stride");
    e.givenKeys = o.keys();
    e.minBoneWeight = minBoneWeight;
    e.start = start;
    e.end = end;
    return e;
}

} // namespace detail

} // namespace mfx::scene
