// The effects of a scene file: the keys every effect has, each kind's own keys and defaults, and
// which keys belong to which kinds (README.md "Scene files" and "The effects, one at a time").
#include "core/scene/effect_keys.h"

#include <set>

namespace mfx::scene {

namespace detail {

namespace {

const std::vector<std::string> kCommonEffectKeys = {
    "type", "name", "bones", "meshes", "min_bone_weight", "start", "end"};
const std::vector<std::string> kTrajectoryKeys = {
    "sub_samples", "lifetime", "stride", "colour", "alpha_start", "alpha_end", "alpha_power"};
const std::vector<std::string> kSmokeKeys = {
    "grid",         "cell_size",    "jacobi",          "fade",   "drag",     "steps_per_second",
    "buoyancy",     "vorticity",    "impulse_k",       "radius", "strength", "emission",
    "surface_step", "max_emitters", "sleep_threshold", "follow"};
// Smith 2016, Sec. 4.3 and 5.3: the afterimage smear's settings.
const std::vector<std::string> kAfterimageKeys = {
    "variant",     "strength_character", "strength_animation",
    "random_min",  "random_max",         "random_threshold",
    "taper",       "min_speed",          "relative_speed",
    "afterimages", "influence_power"};
// Wloka and Zeleznik 1996, Sec. 3.4 and 4.2: the swept volume's settings.
const std::vector<std::string> kSweptKeys = {"filter", "segments", "alpha_floor"};
// Jones 2004, Sec. 3.2.2, 3.2.4 and 3.3: the silhouette shell's settings.
const std::vector<std::string> kShellKeys = {"subdivisions", "blur_time", "initial_alpha",
                                             "fade_out", "edge_rule"};

void readCommonEffectKeys(const Object& o, size_t index, const std::string& type, EffectSpec& e) {
    e.name = o.string("name", type + "#" + std::to_string(index));
    e.bones = o.strings("bones");
    e.meshes = o.strings("meshes");
    e.automaticBones = !o.has("bones") && !o.has("meshes");
    e.automaticStride = !o.has("stride");
    e.givenKeys = o.keys();
    e.minBoneWeight = float(o.number("min_bone_weight", e.minBoneWeight, 0.0, 1.0, true));
    e.start = float(o.number("start", e.start, 0.0, 1e5));
    e.end = o.optionalNumber("end", 0.0, 1e5);
    if (e.end && *e.end <= e.start)
        fail(o.at("end"),
             formatNumber(*e.end) + " is not after start (" + formatNumber(e.start) + ")");
}

// An afterimage_smear effect (Smith 2016): the common keys, colour and alpha, and the smear's own.
void readAfterimage(const Object& o, size_t index, const std::string& type, EffectSpec& e) {
    std::vector<std::string> allowed = kCommonEffectKeys;
    allowed.insert(allowed.end(),
                   {"stride", "colour", "alpha_start", "alpha_end", "alpha_power", "width"});
    allowed.insert(allowed.end(), kAfterimageKeys.begin(), kAfterimageKeys.end());
    std::vector<std::string> elsewhere = kSmokeKeys;
    elsewhere.insert(elsewhere.end(), {"sub_samples", "lifetime", "size"});
    elsewhere.insert(elsewhere.end(), kSweptKeys.begin(), kSweptKeys.end());
    elsewhere.insert(elsewhere.end(), kShellKeys.begin(), kShellKeys.end());
    o.onlyKeys(allowed, elsewhere, "not a key of " + type + " effects");
    readCommonEffectKeys(o, index, type, e);

    AfterimageSpec& a = e.afterimage;
    const std::string variant = o.choice("variant", "smear", {"smear", "speed_lines", "multi"});
    a.variant = variant == "smear"         ? AfterimageVariant::Smear
                : variant == "speed_lines" ? AfterimageVariant::SpeedLines
                                           : AfterimageVariant::Multi;
    for (const char* key : {"width", "stride"})
        if (o.has(key) && a.variant != AfterimageVariant::SpeedLines)
            fail(o.at(key),
                 "only for \"variant\": \"speed_lines\" (the variant is \"" + variant + "\")");
    for (const char* key : {"afterimages", "influence_power"})
        if (o.has(key) && a.variant != AfterimageVariant::Multi)
            fail(o.at(key), "only for \"variant\": \"multi\" (the variant is \"" + variant + "\")");

    // Per-variant defaults: the smear is the mesh itself, opaque; lines and arcs fade out behind.
    e.stride = 1;
    e.alphaStart = 1.0f;
    e.alphaEnd = a.variant == AfterimageVariant::Smear ? 1.0f : 0.0f;
    e.width = 0.008f;
    if (a.variant == AfterimageVariant::SpeedLines) {
        e.colour = {1.0f, 0.95f, 0.8f, 1.0f};
        e.useMeshColour = false;
    }
    if (o.has("colour")) {
        e.colour = o.colour("colour", e.colour);
        e.useMeshColour = false;
    }
    e.stride = o.integer("stride", e.stride, 1, 1000);
    e.alphaStart = float(o.number("alpha_start", e.alphaStart, 0.0, 1.0));
    e.alphaEnd = float(o.number("alpha_end", e.alphaEnd, 0.0, 1.0));
    e.alphaPower = float(o.number("alpha_power", e.alphaPower, 0.0, 16.0, true));
    e.width = float(o.number("width", e.width, 0.0, 1.0, true));

    a.strengthCharacter = float(o.number("strength_character", a.strengthCharacter, 0.0, 1000.0));
    a.strengthAnimation = float(o.number("strength_animation", a.strengthAnimation, 0.0, 1000.0));
    a.randomMin = float(o.number("random_min", a.randomMin, 0.0, 1.0));
    a.randomMax = float(o.number("random_max", a.randomMax, 0.0, 1.0));
    if (a.randomMin > a.randomMax)
        fail(o.at("random_min"), formatNumber(a.randomMin) + " is more than random_max (" +
                                     formatNumber(a.randomMax) + ")");
    a.randomThreshold = float(o.number("random_threshold", a.randomThreshold, 0.0, 1.0));
    a.taper = float(o.number("taper", a.taper, 0.0, 64.0));
    a.minSpeed = float(o.number("min_speed", a.minSpeed, 0.0, 1e4));
    a.relativeSpeed = float(o.number("relative_speed", a.relativeSpeed, 0.0, 1.0));
    a.afterimages = o.integer("afterimages", a.afterimages, 1, 16);
    a.influencePower = float(o.number("influence_power", a.influencePower, 0.0, 64.0));
}

// A swept_volume effect (Wloka and Zeleznik 1996): the common keys, colour, quads per segment
// and the volume's own.
void readSweptVolume(const Object& o, size_t index, const std::string& type, EffectSpec& e) {
    std::vector<std::string> allowed = kCommonEffectKeys;
    allowed.insert(allowed.end(), {"colour", "sub_samples"});
    allowed.insert(allowed.end(), kSweptKeys.begin(), kSweptKeys.end());
    std::vector<std::string> elsewhere = kSmokeKeys;
    elsewhere.insert(elsewhere.end(), kAfterimageKeys.begin(), kAfterimageKeys.end());
    elsewhere.insert(elsewhere.end(), kShellKeys.begin(), kShellKeys.end());
    elsewhere.insert(elsewhere.end(), {"lifetime", "stride", "alpha_start", "alpha_end",
                                       "alpha_power", "width", "size"});
    o.onlyKeys(allowed, elsewhere, "not a key of " + type + " effects");
    readCommonEffectKeys(o, index, type, e);

    SweptVolumeSpec& v = e.swept;
    const std::string filter = o.choice("filter", "ramp", {"box", "ramp", "triangle", "gaussian"});
    v.filter = filter == "box"        ? SweptFilter::Box
               : filter == "ramp"     ? SweptFilter::Ramp
               : filter == "triangle" ? SweptFilter::Triangle
                                      : SweptFilter::Gaussian;
    v.segments = o.integer("segments", v.segments, 1, 16);
    v.alphaFloor = float(o.number("alpha_floor", v.alphaFloor, 0.0, 1.0));
    e.subSamples = o.integer("sub_samples", 4, 1, 16);
    if (o.has("colour")) {
        e.colour = o.colour("colour", e.colour);
        e.useMeshColour = false;
    }
}

// A silhouette_shell effect (Jones 2004): the common keys, colour and the shell's own.
void readSilhouetteShell(const Object& o, size_t index, const std::string& type, EffectSpec& e) {
    std::vector<std::string> allowed = kCommonEffectKeys;
    allowed.push_back("colour");
    allowed.insert(allowed.end(), kShellKeys.begin(), kShellKeys.end());
    std::vector<std::string> elsewhere = kSmokeKeys;
    elsewhere.insert(elsewhere.end(), kAfterimageKeys.begin(), kAfterimageKeys.end());
    elsewhere.insert(elsewhere.end(), kSweptKeys.begin(), kSweptKeys.end());
    elsewhere.insert(elsewhere.end(), {"sub_samples", "lifetime", "stride", "alpha_start",
                                       "alpha_end", "alpha_power", "width", "size"});
    o.onlyKeys(allowed, elsewhere, "not a key of " + type + " effects");
    readCommonEffectKeys(o, index, type, e);

    SilhouetteShellSpec& s = e.shell;
    s.subdivisions = o.integer("subdivisions", s.subdivisions, 1, 32);
    if (o.has("blur_time")) s.blurTime = float(o.number("blur_time", 0.2, 0.0, 60.0, true));
    s.initialAlpha = float(o.number("initial_alpha", s.initialAlpha, 0.0, 1.0));
    s.fadeOut = o.integer("fade_out", s.fadeOut, 0, 1000);
    const std::string rule = o.choice("edge_rule", "back", {"back", "front"});
    s.edgeRule = rule == "back" ? ShellEdgeRule::Back : ShellEdgeRule::Front;
    if (o.has("colour")) {
        e.colour = o.colour("colour", e.colour);
        e.useMeshColour = false;
    }
}

} // namespace

void readEffect(const Object& o, size_t index, EffectSpec& e) {
    if (!o.has("type"))
        fail(o.at("type"), "missing; every effect needs a type: speed_lines, motion_blur, "
                           "motion_particles, smoke, afterimage_smear, swept_volume or "
                           "silhouette_shell");
    const std::string type = o.choice("type", "",
                                      {"speed_lines", "motion_blur", "motion_particles", "smoke",
                                       "afterimage_smear", "swept_volume", "silhouette_shell"});
    e.type = type == "speed_lines"        ? EffectType::SpeedLines
             : type == "motion_blur"      ? EffectType::MotionBlur
             : type == "motion_particles" ? EffectType::MotionParticles
             : type == "smoke"            ? EffectType::Smoke
             : type == "afterimage_smear" ? EffectType::AfterimageSmear
             : type == "swept_volume"     ? EffectType::SweptVolume
                                          : EffectType::SilhouetteShell;
    std::vector<std::string> allowed = kCommonEffectKeys;
    allowed.insert(allowed.end(), kTrajectoryKeys.begin(), kTrajectoryKeys.end());
    std::vector<std::string> elsewhere;
    if (e.type == EffectType::AfterimageSmear) {
        readAfterimage(o, index, type, e);
        return;
    }
    if (e.type == EffectType::SweptVolume) {
        readSweptVolume(o, index, type, e);
        return;
    }
    if (e.type == EffectType::SilhouetteShell) {
        readSilhouetteShell(o, index, type, e);
        return;
    }
    elsewhere = kAfterimageKeys;
    elsewhere.insert(elsewhere.end(), kSweptKeys.begin(), kSweptKeys.end());
    elsewhere.insert(elsewhere.end(), kShellKeys.begin(), kShellKeys.end());
    if (e.type == EffectType::Smoke) {
        allowed.insert(allowed.end(), kSmokeKeys.begin(), kSmokeKeys.end());
        elsewhere.insert(elsewhere.end(), {"width", "size"});
    } else {
        elsewhere.insert(elsewhere.end(), kSmokeKeys.begin(), kSmokeKeys.end());
        if (e.type == EffectType::SpeedLines)
            allowed.push_back("width");
        else
            elsewhere.push_back("width");
        if (e.type == EffectType::MotionParticles)
            allowed.push_back("size");
        else
            elsewhere.push_back("size");
    }
    o.onlyKeys(allowed, elsewhere, "not a key of " + type + " effects");
    readCommonEffectKeys(o, index, type, e);

    // Per-type defaults before the keys that override them.
    if (e.type == EffectType::SpeedLines) {
        e.stride = 6;
        e.colour = {1.0f, 0.85f, 0.3f, 1.0f};
        e.useMeshColour = false;
    } else if (e.type == EffectType::MotionBlur) {
        e.lifetime = 6;
        e.alphaStart = 0.55f;
    } else if (e.type == EffectType::MotionParticles) {
        e.stride = 3;
        e.colour = {0.6f, 0.9f, 1.0f, 1.0f};
        e.useMeshColour = false;
    } else {
        e.colour = {0.85f, 0.35f, 0.15f, 1.0f};
        e.useMeshColour = false;
        e.lifetime = 2;
    }
    e.subSamples = o.integer("sub_samples", e.subSamples, 1, 16);
    e.lifetime = o.integer("lifetime", e.lifetime, 1, 256);
    e.stride = o.integer("stride", e.stride, 1, 1000);
    if (o.has("colour")) {
        e.colour = o.colour("colour", e.colour);
        e.useMeshColour = false;
    }
    e.alphaStart = float(o.number("alpha_start", e.alphaStart, 0.0, 1.0));
    e.alphaEnd = float(o.number("alpha_end", e.alphaEnd, 0.0, 1.0));
    e.alphaPower = float(o.number("alpha_power", e.alphaPower, 0.0, 16.0, true));
    e.width = float(o.number("width", e.width, 0.0, 1.0, true));
    e.size = float(o.number("size", e.size, 0.0, 1.0, true));
    if (e.type != EffectType::Smoke) return;

    if (o.has("grid")) {
        const std::vector<double> g = o.numbers("grid", 3, 3, 4, 256);
        for (int a = 0; a < 3; ++a) {
            if (g[size_t(a)] != std::floor(g[size_t(a)]))
                fail(o.at("grid") + "[" + std::to_string(a) + "]", "expected a whole number");
            e.grid[size_t(a)] = uint32_t(g[size_t(a)]);
        }
    }
    e.cellSize = float(o.number("cell_size", e.cellSize, 0.0, 10.0, true));
    e.jacobi = o.integer("jacobi", e.jacobi, 0, 10000);
    e.fade = float(o.number("fade", e.fade, 0.0, 100.0));
    e.drag = float(o.number("drag", e.drag, 0.0, 100.0));
    e.stepsPerSecond = float(o.number("steps_per_second", e.stepsPerSecond, 1.0, 1000.0));
    e.follow = o.boolean("follow", e.follow);
    e.buoyancy = float(o.number("buoyancy", e.buoyancy, -100.0, 100.0));
    e.vorticity = float(o.number("vorticity", e.vorticity, 0.0, 100.0));
    e.impulseScale = float(o.number("impulse_k", e.impulseScale, 0.0, 100.0));
    e.radius = float(o.number("radius", e.radius, 0.0, 10.0, true));
    e.strength = float(o.number("strength", e.strength, 0.0, 1000.0));
    e.emission = o.choice("emission", "vertices", {"vertices", "surface"}) == "surface"
                     ? Emission::Surface
                     : Emission::Vertices;
    e.surfaceStep = float(o.number("surface_step", e.surfaceStep, 0.0, 1.0, true));
    e.maxEmitters = o.integer("max_emitters", e.maxEmitters, 1, 4096);
    e.sleepThreshold = float(o.number("sleep_threshold", e.sleepThreshold, 0.0, 1.0, true));
}

} // namespace detail

const char* effectTypeName(EffectType type) {
    switch (type) {
    case EffectType::SpeedLines:
        return "speed_lines";
    case EffectType::MotionBlur:
        return "motion_blur";
    case EffectType::MotionParticles:
        return "motion_particles";
    case EffectType::Smoke:
        return "smoke";
    case EffectType::AfterimageSmear:
        return "afterimage_smear";
    case EffectType::SweptVolume:
        return "swept_volume";
    case EffectType::SilhouetteShell:
        return "silhouette_shell";
    }
    return "speed_lines";
}

} // namespace mfx::scene
