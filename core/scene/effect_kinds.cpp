#include "core/scene/effect_kinds.h"

#include "core/scene/effect_kind_headers.h" // generated: every header of core/scene/kinds
#include "core/scene/json_object.h"
#include "core/scene/scene_params.h"

#include <stdexcept>

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
        entry<ImpactSpec>(),          // where a blow lands: sparks, flash, ring, hit-stop
    };
    return kinds;
}

const std::vector<std::string>& commonEffectKeys() {
    static const std::vector<std::string> keys = {
        "type", "name", "character", "bones", "meshes", "min_bone_weight", "start", "end"};
    return keys;
}

namespace detail {

namespace {

// The keys every effect has.
struct CommonKeys {
    std::string name;
    std::string character;
    std::vector<std::string> bones, meshes;
    float minBoneWeight = 0.5f;
    float start = 0.0f;
    std::optional<float> end;
    bool automaticBones = false, automaticStride = false; // what fitScene chooses
};

CommonKeys readCommonKeys(const Object& o, const std::string& type, size_t index) {
    CommonKeys c;
    c.name = o.string("name", type + "#" + std::to_string(index));
    // Checked against the scene's characters once they are all read (scene.cpp).
    c.character = o.characterName("character");
    c.bones = o.strings("bones");
    c.meshes = o.strings("meshes");
    const bool bones = o.has("bones"), meshes = o.has("meshes");
    c.automaticBones = !bones && !meshes;
    c.automaticStride = !o.has("stride");
    c.minBoneWeight = float(o.number("min_bone_weight", 0.5, 0.0, 1.0, true));
    c.start = float(o.number("start", 0.0, 0.0, 1e5));
    if (const std::optional<double> end = o.optionalNumber("end", 0.0, 1e5)) c.end = float(*end);
    if (c.end && *c.end <= c.start)
        fail(o.at("end"),
             formatNumber(*c.end) + " is not after start (" + formatNumber(c.start) + ")");
    return c;
}

std::vector<std::string> typeNames() {
    std::vector<std::string> types;
    for (const EffectKindEntry& kind : effectKinds())
        types.push_back(kind.type);
    return types;
}

} // namespace

EffectSpec readEffect(const Object& o, size_t index) {
    const std::vector<std::string> types = typeNames();
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
    const CommonKeys common = readCommonKeys(o, type, index);
    EffectSpec e(kind.parse(o));
    e.name = common.name;
    e.character = common.character;
    e.bones = common.bones;
    e.meshes = common.meshes;
    e.automaticBones = common.automaticBones;
    e.automaticStride = common.automaticStride;
    e.givenKeys = o.keys();
    e.minBoneWeight = common.minBoneWeight;
    e.start = common.start;
    e.end = common.end;
    return e;
}

} // namespace detail

std::vector<ParamInfo> effectParams(const std::string& type, const nlohmann::json& effect) {
    const auto kind = std::find_if(effectKinds().begin(), effectKinds().end(),
                                   [&](const EffectKindEntry& k) { return type == k.type; });
    if (kind == effectKinds().end()) throw std::invalid_argument("no effect type \"" + type + "\"");
    detail::Description described;
    ParamInfo typeKey;
    typeKey.key = "type";
    typeKey.type = ParamInfo::Type::Choice;
    typeKey.choices = detail::typeNames();
    typeKey.fallback = type;
    described.params.push_back(typeKey);
    const detail::Object o(described, effect);
    detail::readCommonKeys(o, type, 0);
    kind->parse(o);
    return detail::uniqueParams(described);
}

} // namespace mfx::scene
