#include "core/scene/kinds/trail_effects.h"

#include "core/scene/json_object.h"

namespace mfx::scene {

using detail::Object;

namespace {

// A kind with a trail, its trail keys read.
template <class Kind>
std::unique_ptr<Kind> readTrailKind(const Object& o) {
    auto e = std::make_unique<Kind>();
    readTrail(o, e->trail);
    return e;
}

} // namespace

std::vector<std::string> trailKeys(std::initializer_list<const char*> extra) {
    std::vector<std::string> keys = {"sub_samples", "lifetime",  "stride",     "colour",
                                     "alpha_start", "alpha_end", "alpha_power"};
    keys.insert(keys.end(), extra.begin(), extra.end());
    return keys;
}

void readTrail(const Object& o, TrailSpec& t) {
    t.subSamples = o.integer("sub_samples", t.subSamples, 1, 16);
    t.lifetime = o.integer("lifetime", t.lifetime, 1, 256);
    t.stride = o.integer("stride", t.stride, 1, 1000);
    if (o.has("colour")) {
        t.colour = o.colour("colour", t.colour);
        t.useMeshColour = false;
    }
    t.alphaStart = float(o.number("alpha_start", t.alphaStart, 0.0, 1.0));
    t.alphaEnd = float(o.number("alpha_end", t.alphaEnd, 0.0, 1.0));
    t.alphaPower = float(o.number("alpha_power", t.alphaPower, 0.0, 16.0, true));
}

std::unique_ptr<EffectKindSpec> SpeedLinesSpec::parse(const Object& o) {
    auto e = readTrailKind<SpeedLinesSpec>(o);
    e->width = float(o.number("width", e->width, 0.0, 1.0, true));
    return e;
}

std::unique_ptr<EffectKindSpec> MotionBlurSpec::parse(const Object& o) {
    return readTrailKind<MotionBlurSpec>(o);
}

std::unique_ptr<EffectKindSpec> MotionParticlesSpec::parse(const Object& o) {
    auto e = readTrailKind<MotionParticlesSpec>(o);
    e->size = float(o.number("size", e->size, 0.0, 1.0, true));
    return e;
}

} // namespace mfx::scene
