#include "core/scene/kinds/trail_effects.h"

#include "core/enum_names.h"
#include "core/scene/json_object.h"
#include "core/scene/ribbon_texture.h"

namespace mfx::scene {

using detail::fail;
using detail::formatNumber;
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

std::vector<std::string> ribbonKeys() {
    return {"colour_over_life", "width_over_life",
            "intensity",        "blend",
            "depth_fade",       "core",
            "facing",           "shape"};
}

namespace {

// Stops of an array of 2-8 objects {"at": u, <valueKey>: ...}, `at` rising from 0 to 1 over
// `span`.
template <class Stop, class ReadValue>
std::vector<Stop> readStops(const Object& o, const std::string& key, const char* valueKey,
                            ReadValue readValue, const char* span = "where in life") {
    std::vector<Stop> stops;
    if (!o.has(key)) return stops;
    const std::vector<Object> entries = o.objects(key, 2, kMaxRibbonStops);
    for (size_t i = 0; i < entries.size(); ++i) {
        const Object& e = entries[i];
        e.onlyKeys({"at", valueKey});
        if (!e.has("at"))
            fail(e.at("at"), std::string("missing; each stop says ") + span + " (0..1) it is");
        if (!e.has(valueKey)) fail(e.at(valueKey), "missing");
        Stop stop;
        stop.at = float(e.number("at", 0.0, 0.0, 1.0));
        if (i > 0 && stop.at < stops.back().at)
            fail(e.at("at"), formatNumber(stop.at) + " is before the previous stop's " +
                                 formatNumber(stops.back().at) +
                                 "; \"at\" rises from stop to stop");
        readValue(e, stop);
        stops.push_back(stop);
    }
    return stops;
}

template <class Stop, class Value, class Mix>
Value valueOf(const std::vector<Stop>& stops, float u, Value Stop::*member, Mix mix) {
    if (u <= stops.front().at) return stops.front().*member;
    for (size_t i = 1; i < stops.size(); ++i)
        if (u <= stops[i].at) {
            const float span = stops[i].at - stops[i - 1].at;
            const float f = span > 0.0f ? (u - stops[i - 1].at) / span : 1.0f;
            return mix(stops[i - 1].*member, stops[i].*member, f);
        }
    return stops.back().*member;
}

// The keys ribbons, particles and (without a size or a depth fade) volumes have:
// colour_over_life, <size>_over_life with its stops' <size> values, intensity, blend and
// depth_fade.
void readLook(const Object& o, RibbonLook& r, const char* size) {
    r.colourOverLife = readGradientStops(o, "colour_over_life", "where in life");
    r.intensity = float(o.number("intensity", r.intensity, 0.0, 1000.0));
    r.additive =
        o.choice("blend", r.additive ? "additive" : "alpha", {"alpha", "additive"}) == "additive";
    if (!size) return;
    r.widthOverLife = readStops<CurveStop>(o, std::string(size) + "_over_life", size,
                                           [size](const Object& e, CurveStop& s) {
                                               s.value = float(e.number(size, 1.0, 0.0, 100.0));
                                           });
    r.depthFade = float(o.number("depth_fade", r.depthFade, 0.0, 10.0));
}

} // namespace

std::vector<GradientStop> readGradientStops(const Object& o, const std::string& key,
                                            const char* span) {
    return readStops<GradientStop>(
        o, key, "colour",
        [](const Object& e, GradientStop& s) { s.colour = e.colour("colour", s.colour); }, span);
}

std::vector<std::string> volumeLookKeys() {
    return {"colour_over_life", "intensity", "blend", "rim", "rim_colour"};
}

void readVolumeLook(const Object& o, VolumeLook& v) {
    RibbonLook shared;
    readLook(o, shared, nullptr);
    v.colourOverLife = std::move(shared.colourOverLife);
    v.intensity = shared.intensity;
    v.additive = shared.additive;
    v.rim = float(o.number("rim", v.rim, 0.0, 1000.0));
    v.rimColour = glm::vec3(o.colour("rim_colour", glm::vec4(v.rimColour, 1.0f)));
}

std::vector<std::string> particleLookKeys() {
    return {"colour_over_life", "size_over_life", "intensity", "blend", "depth_fade"};
}

void readParticleLook(const Object& o, RibbonLook& r) {
    readLook(o, r, "size");
}

void readRibbon(const Object& o, RibbonLook& r, bool sheets) {
    readLook(o, r, "width");
    r.core = float(o.number("core", r.core, 0.0, 1.0));
    r.bladeFacing =
        o.choice("facing", r.bladeFacing ? "blade" : "camera", {"camera", "blade"}) == "blade";
    std::vector<std::string> shapes = {"flat", "tube"};
    if (sheets) shapes.push_back("sheet");
    const std::string shape = o.choice("shape",
                                       r.sheet  ? "sheet"
                                       : r.tube ? "tube"
                                                : "flat",
                                       shapes);
    r.tube = shape == "tube";
    r.sheet = shape == "sheet";
}

std::vector<std::string> ribbonTextureKeys() {
    return {"texture",        "texture_uv",        "texture_repeats", "texture_tile",
            "texture_scroll", "erosion_over_life", "erosion_softness"};
}

namespace {

constexpr NamedValue<TextureUv> kTextureUvNames[] = {{TextureUv::Stretch, "stretch"},
                                                     {TextureUv::PerSegment, "per_segment"},
                                                     {TextureUv::Tiled, "tiled"},
                                                     {TextureUv::Distance, "distance"}};

} // namespace

const char* textureUvName(TextureUv uv) {
    return nameOf(uv, kTextureUvNames);
}

void readRibbonTexture(const Object& o, RibbonTexture& t) {
    t.file = o.string("texture", t.file);
    if (const std::string problem = textureNameProblem(t.file); !problem.empty())
        fail(o.at("texture"), problem);
    std::vector<std::string> names;
    for (const auto& [value, name] : kTextureUvNames)
        names.push_back(name);
    t.uv =
        mfx::valueOf(o.choice("texture_uv", textureUvName(t.uv), names), kTextureUvNames).value();
    t.repeats = float(o.number("texture_repeats", t.repeats, 0.0, 1000.0, true));
    t.tileLength = float(o.number("texture_tile", t.tileLength, 0.0, 100.0, true));
    t.scroll = float(o.number("texture_scroll", t.scroll, -1000.0, 1000.0));
    t.erosionOverLife = readStops<CurveStop>(
        o, "erosion_over_life", "threshold", [](const Object& e, CurveStop& s) {
            s.value = float(e.number("threshold", 0.0, 0.0, 1.0));
        });
    t.erosionSoftness = float(o.number("erosion_softness", t.erosionSoftness, 0.0, 1.0, true));
}

glm::vec4 colourAt(const std::vector<GradientStop>& stops, float u) {
    return valueOf(stops, u, &GradientStop::colour,
                   [](glm::vec4 a, glm::vec4 b, float f) { return glm::mix(a, b, f); });
}

float valueAt(const std::vector<CurveStop>& stops, float u) {
    return valueOf(stops, u, &CurveStop::value,
                   [](float a, float b, float f) { return a + (b - a) * f; });
}

std::unique_ptr<EffectKindSpec> SpeedLinesSpec::parse(const Object& o) {
    auto e = readTrailKind<SpeedLinesSpec>(o);
    e->width = float(o.number("width", e->width, 0.0, 1.0, true));
    readRibbon(o, e->ribbon, true);
    readRibbonTexture(o, e->ribbon.texture);
    e->trail.twoEnds = e->ribbon.sheet;
    return e;
}

std::unique_ptr<EffectKindSpec> MotionBlurSpec::parse(const Object& o) {
    auto e = readTrailKind<MotionBlurSpec>(o);
    readVolumeLook(o, e->look);
    return e;
}

std::unique_ptr<EffectKindSpec> MotionParticlesSpec::parse(const Object& o) {
    auto e = readTrailKind<MotionParticlesSpec>(o);
    e->size = float(o.number("size", e->size, 0.0, 1.0, true));
    readParticleLook(o, e->look);
    return e;
}

} // namespace mfx::scene
