#include "core/scene/kinds/swept_volume_effect.h"

#include "core/scene/json_object.h"

namespace mfx::scene {

// Wloka and Zeleznik 1996, Sec. 3.4 and 4.2: the volume's settings.
std::vector<std::string> SweptVolumeSpec::keys() {
    std::vector<std::string> keys = {"colour", "sub_samples", "filter", "segments", "alpha_floor"};
    for (const std::string& l : volumeLookKeys())
        keys.push_back(l);
    return keys;
}

std::unique_ptr<EffectKindSpec> SweptVolumeSpec::parse(const detail::Object& o) {
    auto v = std::make_unique<SweptVolumeSpec>();
    const std::string filter = o.choice("filter", "ramp", {"box", "ramp", "triangle", "gaussian"});
    v->filter = filter == "box"        ? SweptFilter::Box
                : filter == "ramp"     ? SweptFilter::Ramp
                : filter == "triangle" ? SweptFilter::Triangle
                                       : SweptFilter::Gaussian;
    v->segments = o.integer("segments", v->segments, 1, 16);
    v->alphaFloor = float(o.number("alpha_floor", v->alphaFloor, 0.0, 1.0));
    v->subSamples = o.integer("sub_samples", v->subSamples, 1, 16);
    if (o.has("colour")) {
        v->colour = o.colour("colour", v->colour);
        v->useMeshColour = false;
    }
    readVolumeLook(o, v->look);
    return v;
}

} // namespace mfx::scene
