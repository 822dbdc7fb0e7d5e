#include "core/scene/kinds/afterimage_effect.h"

#include "core/scene/json_object.h"

#include <algorithm>

namespace mfx::scene {

using detail::fail;
using detail::formatNumber;
using detail::Object;

// Smith 2016, Sec. 4.3 and 5.3: the smear's settings, and how it looks.
std::vector<std::string> AfterimageSpec::keys() {
    std::vector<std::string> keys = {"stride",
                                     "colour",
                                     "alpha_start",
                                     "alpha_end",
                                     "alpha_power",
                                     "width",
                                     "variant",
                                     "strength_character",
                                     "strength_animation",
                                     "random_min",
                                     "random_max",
                                     "random_threshold",
                                     "taper",
                                     "min_speed",
                                     "relative_speed",
                                     "afterimages",
                                     "influence_power"};
    // The ribbon's (speed_lines) and the volume's (smear, multi) look, each key once.
    for (const std::vector<std::string>& look : {ribbonKeys(), volumeLookKeys()})
        for (const std::string& k : look)
            if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
    return keys;
}

std::unique_ptr<EffectKindSpec> AfterimageSpec::parse(const Object& o) {
    auto a = std::make_unique<AfterimageSpec>();
    const std::string variant = o.choice("variant", "smear", {"smear", "speed_lines", "multi"});
    a->variant = variant == "smear"         ? AfterimageVariant::Smear
                 : variant == "speed_lines" ? AfterimageVariant::SpeedLines
                                            : AfterimageVariant::Multi;
    const std::vector<std::string> volumeKeys = volumeLookKeys();
    auto isVolumeKey = [&](const std::string& key) {
        return std::find(volumeKeys.begin(), volumeKeys.end(), key) != volumeKeys.end();
    };
    std::vector<std::string> lineKeys = ribbonKeys();
    lineKeys.insert(lineKeys.end(), {"width", "stride"});
    for (const std::string& key : lineKeys)
        if (o.given(key) && !isVolumeKey(key) && a->variant != AfterimageVariant::SpeedLines)
            fail(o.at(key),
                 "only for \"variant\": \"speed_lines\" (the variant is \"" + variant + "\")");
    for (const std::string& key : volumeKeys)
        if (o.given(key) && !std::count(lineKeys.begin(), lineKeys.end(), key) &&
            a->variant == AfterimageVariant::SpeedLines)
            fail(o.at(key), "only for the \"smear\" and \"multi\" variants (the variant is \"" +
                                variant + "\")");
    for (const char* key : {"afterimages", "influence_power"})
        if (o.given(key) && a->variant != AfterimageVariant::Multi)
            fail(o.at(key), "only for \"variant\": \"multi\" (the variant is \"" + variant + "\")");

    // Per-variant defaults: the smear is the mesh itself, opaque; lines and arcs fade out behind.
    a->alphaEnd = a->variant == AfterimageVariant::Smear ? 1.0f : 0.0f;
    if (a->variant == AfterimageVariant::SpeedLines) {
        a->colour = {1.0f, 0.95f, 0.8f, 1.0f};
        a->useMeshColour = false;
    }
    if (o.has("colour")) {
        a->colour = o.colour("colour", a->colour);
        a->useMeshColour = false;
    }
    a->alphaStart = float(o.number("alpha_start", a->alphaStart, 0.0, 1.0));
    a->alphaEnd = float(o.number("alpha_end", a->alphaEnd, 0.0, 1.0));
    a->alphaPower = float(o.number("alpha_power", a->alphaPower, 0.0, 16.0, true));
    if (a->variant == AfterimageVariant::SpeedLines) {
        a->stride = o.integer("stride", a->stride, 1, 1000);
        a->width = float(o.number("width", a->width, 0.0, 1.0, true));
        readRibbon(o, a->ribbon);
    } else {
        readVolumeLook(o, a->look);
    }

    a->strengthCharacter = float(o.number("strength_character", a->strengthCharacter, 0.0, 1000.0));
    a->strengthAnimation = float(o.number("strength_animation", a->strengthAnimation, 0.0, 1000.0));
    a->randomMin = float(o.number("random_min", a->randomMin, 0.0, 1.0));
    a->randomMax = float(o.number("random_max", a->randomMax, 0.0, 1.0));
    if (a->randomMin > a->randomMax)
        fail(o.at("random_min"), formatNumber(a->randomMin) + " is more than random_max (" +
                                     formatNumber(a->randomMax) + ")");
    a->randomThreshold = float(o.number("random_threshold", a->randomThreshold, 0.0, 1.0));
    a->taper = float(o.number("taper", a->taper, 0.0, 64.0));
    a->minSpeed = float(o.number("min_speed", a->minSpeed, 0.0, 1e4));
    a->relativeSpeed = float(o.number("relative_speed", a->relativeSpeed, 0.0, 1.0));
    if (a->variant == AfterimageVariant::Multi) {
        a->afterimages = o.integer("afterimages", a->afterimages, 1, 16);
        a->influencePower = float(o.number("influence_power", a->influencePower, 0.0, 64.0));
    }
    return a;
}

} // namespace mfx::scene
