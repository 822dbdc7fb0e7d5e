#include "core/scene/scene.h"

#include "core/anim/bone_groups.h"
#include "core/anim/fighter.h"
#include "core/anim/gltf_import.h"
#include "core/scene/scene_fit.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace mfx::scene {

namespace {

using json = nlohmann::json;

// Thrown inside the parser only, caught at its top and turned into an Error.
struct SceneError {
    std::string message;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw SceneError{path + ": " + what};
}

std::string typeOf(const json& j) {
    if (j.is_null()) return "null";
    if (j.is_boolean()) return "a boolean";
    if (j.is_number()) return "a number";
    if (j.is_string()) return "a string";
    if (j.is_array()) return "an array";
    return "an object";
}

std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names)
        out += (out.empty() ? "" : ", ") + n;
    return out;
}

std::string formatNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// One JSON object being read, with its key path for errors.
class Object {
public:
    Object(const json& j, std::string path) : j_(j), path_(std::move(path)) {
        if (!j_.is_object())
            fail(path_.empty() ? "scene" : path_, "expected an object, got " + typeOf(j_));
    }

    // Refuses keys outside `allowed`; `elsewhere` are keys that exist for other effect types.
    void onlyKeys(const std::vector<std::string>& allowed,
                  const std::vector<std::string>& elsewhere = {},
                  const std::string& elsewhereWhy = {}) const {
        for (auto it = j_.begin(); it != j_.end(); ++it) {
            if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
            if (std::find(elsewhere.begin(), elsewhere.end(), it.key()) != elsewhere.end())
                fail(at(it.key()), elsewhereWhy);
            fail(at(it.key()), "unknown key; keys here are: " + join(allowed));
        }
    }

    bool has(const std::string& key) const { return j_.contains(key); }
    std::vector<std::string> keys() const {
        std::vector<std::string> out;
        for (auto it = j_.begin(); it != j_.end(); ++it)
            out.push_back(it.key());
        return out;
    }
    std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
    const json& raw(const std::string& key) const { return j_.at(key); }

    double number(const std::string& key, double fallback, double low, double high,
                  bool lowOpen = false) const {
        if (!has(key)) return fallback;
        return checkNumber(j_.at(key), at(key), low, high, lowOpen);
    }
    std::optional<double> optionalNumber(const std::string& key, double low, double high,
                                         bool lowOpen = false) const {
        if (!has(key) || j_.at(key).is_null()) return std::nullopt;
        return checkNumber(j_.at(key), at(key), low, high, lowOpen);
    }
    uint32_t integer(const std::string& key, uint32_t fallback, uint32_t low, uint32_t high) const {
        if (!has(key)) return fallback;
        return checkInteger(j_.at(key), at(key), low, high);
    }
    bool boolean(const std::string& key, bool fallback) const {
        if (!has(key)) return fallback;
        const json& v = j_.at(key);
        if (!v.is_boolean()) fail(at(key), "expected true or false, got " + typeOf(v));
        return v.get<bool>();
    }
    std::string string(const std::string& key, const std::string& fallback) const {
        if (!has(key)) return fallback;
        const json& v = j_.at(key);
        if (!v.is_string()) fail(at(key), "expected a string, got " + typeOf(v));
        return v.get<std::string>();
    }
    std::string choice(const std::string& key, const std::string& fallback,
                       const std::vector<std::string>& choices) const {
        const std::string v = string(key, fallback);
        if (std::find(choices.begin(), choices.end(), v) == choices.end())
            fail(at(key), "\"" + v + "\" is not one of: " + join(choices));
        return v;
    }
    glm::vec3 vec3(const std::string& key, glm::vec3 fallback, double low = -1e6,
                   double high = 1e6) const {
        if (!has(key)) return fallback;
        const std::vector<double> v = numbers(key, 3, 3, low, high);
        return {float(v[0]), float(v[1]), float(v[2])};
    }
    // An RGB or RGBA colour in [0, 1].
    glm::vec4 colour(const std::string& key, glm::vec4 fallback) const {
        if (!has(key)) return fallback;
        const std::vector<double> v = numbers(key, 3, 4, 0.0, 1.0);
        return {float(v[0]), float(v[1]), float(v[2]), v.size() == 4 ? float(v[3]) : 1.0f};
    }
    std::vector<std::string> strings(const std::string& key) const {
        std::vector<std::string> out;
        if (!has(key)) return out;
        const json& v = j_.at(key);
        if (!v.is_array()) fail(at(key), "expected an array of names, got " + typeOf(v));
        for (size_t i = 0; i < v.size(); ++i) {
            if (!v[i].is_string())
                fail(at(key) + "[" + std::to_string(i) + "]",
                     "expected a name, got " + typeOf(v[i]));
            out.push_back(v[i].get<std::string>());
        }
        return out;
    }
    std::vector<double> numbers(const std::string& key, size_t minCount, size_t maxCount,
                                double low, double high) const {
        const json& v = j_.at(key);
        const std::string count =
            minCount == maxCount ? std::to_string(minCount)
                                 : std::to_string(minCount) + " or " + std::to_string(maxCount);
        if (!v.is_array() || v.size() < minCount || v.size() > maxCount)
            fail(at(key),
                 "expected an array of " + count + " numbers, got " +
                     (v.is_array() ? "an array of " + std::to_string(v.size()) : typeOf(v)));
        std::vector<double> out;
        for (size_t i = 0; i < v.size(); ++i)
            out.push_back(checkNumber(v[i], at(key) + "[" + std::to_string(i) + "]", low, high));
        return out;
    }

private:
    static double checkNumber(const json& v, const std::string& path, double low, double high,
                              bool lowOpen = false) {
        if (!v.is_number()) fail(path, "expected a number, got " + typeOf(v));
        const double d = v.get<double>();
        if (!std::isfinite(d)) fail(path, "must be a finite number");
        if (d < low || d > high || (lowOpen && d == low))
            fail(path, formatNumber(d) + " is outside " + (lowOpen ? "(" : "[") +
                           formatNumber(low) + ", " + formatNumber(high) + "]");
        return d;
    }
    static uint32_t checkInteger(const json& v, const std::string& path, uint32_t low,
                                 uint32_t high) {
        if (!v.is_number()) fail(path, "expected a whole number, got " + typeOf(v));
        const double d = v.get<double>();
        if (!std::isfinite(d) || d != std::floor(d)) fail(path, "expected a whole number");
        if (d < low || d > high)
            fail(path, formatNumber(d) + " is outside " + std::to_string(low) + ".." +
                           std::to_string(high));
        return uint32_t(d);
    }

    const json& j_;
    std::string path_;
};

void readCharacter(const Object& o, CharacterSpec& c) {
    o.onlyKeys({"source", "clip", "start", "end", "speed", "loop", "position", "yaw_degrees",
                "height", "scale"});
    c.source = o.string("source", c.source);
    if (c.source.empty()) fail(o.at("source"), "must name \"fighter\" or a .gltf/.glb file");
    c.clip = o.string("clip", c.clip);
    c.start = float(o.number("start", c.start, 0.0, 1e5));
    c.end = o.optionalNumber("end", 0.0, 1e5);
    if (c.end && *c.end <= c.start)
        fail(o.at("end"),
             formatNumber(*c.end) + " is not after start (" + formatNumber(c.start) + ")");
    c.speed = float(o.number("speed", c.speed, 0.0, 100.0, true));
    c.loop = o.boolean("loop", c.loop);
    c.position = o.vec3("position", c.position);
    c.yawDegrees = float(o.number("yaw_degrees", c.yawDegrees, -3600.0, 3600.0));
    if (o.has("height") && o.has("scale"))
        fail(o.at("scale"), "give height or scale, not both (height: the metres to scale the "
                            "character to; scale: the factor to scale it by)");
    if (const std::optional<double> h = o.optionalNumber("height", 1e-4, 1e4)) c.height = *h;
    if (const std::optional<double> f = o.optionalNumber("scale", 1e-6, 1e6)) c.scale = *f;
}

void readCamera(const Object& o, CameraSpec& c) {
    o.onlyKeys({"position", "target", "fov_degrees", "near", "far"});
    c.position = o.vec3("position", c.position);
    c.target = o.vec3("target", c.target);
    if (glm::length(c.position - c.target) < 1e-6f)
        fail(o.at("target"), "is where the camera is; the camera needs a direction to look in");
    c.fovDegrees = float(o.number("fov_degrees", c.fovDegrees, 1.0, 179.0));
    c.nearPlane = float(o.number("near", c.nearPlane, 0.0, 1e4, true));
    c.farPlane = float(o.number("far", c.farPlane, 0.0, 1e6, true));
    if (c.farPlane <= c.nearPlane)
        fail(o.at("far"),
             formatNumber(c.farPlane) + " is not beyond near (" + formatNumber(c.nearPlane) + ")");
}

void readLight(const Object& o, LightSpec& l) {
    o.onlyKeys({"direction", "colour", "intensity", "shadow"});
    l.direction = o.vec3("direction", l.direction);
    if (glm::length(l.direction) < 1e-6f) fail(o.at("direction"), "must not be zero");
    l.colour = glm::vec3(o.colour("colour", glm::vec4(l.colour, 1.0f)));
    l.intensity = float(o.number("intensity", l.intensity, 0.0, 100.0));
    l.shadow = o.boolean("shadow", l.shadow);
}

void readStage(const Object& o, StageSpec& s) {
    o.onlyKeys({"floor", "backdrop", "floor_colour", "backdrop_colour"});
    s.floor = o.boolean("floor", s.floor);
    s.backdrop = o.boolean("backdrop", s.backdrop);
    s.floorColour = glm::vec3(o.colour("floor_colour", glm::vec4(s.floorColour, 1.0f)));
    s.backdropColour = glm::vec3(o.colour("backdrop_colour", glm::vec4(s.backdropColour, 1.0f)));
}

void readOutput(const Object& o, OutputSpec& out) {
    o.onlyKeys({"width", "height", "fps", "frames"});
    out.width = o.integer("width", out.width, 16, 8192);
    out.height = o.integer("height", out.height, 16, 8192);
    out.fps = float(o.number("fps", out.fps, 1.0, 240.0));
    if (o.has("frames") && !o.raw("frames").is_null())
        out.frames = o.integer("frames", 1, 1, 100000);
}

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

Scene readScene(const json& doc, const std::string& where) {
    Scene s;
    s.file = where;
    const Object top(doc, "");
    top.onlyKeys({"character", "camera", "lights", "stage", "output", "effects"});
    if (top.has("character")) readCharacter(Object(top.raw("character"), "character"), s.character);
    if (top.has("camera")) readCamera(Object(top.raw("camera"), "camera"), s.camera);
    s.camera.automatic = !top.has("camera");
    if (top.has("lights")) {
        const json& lights = top.raw("lights");
        if (!lights.is_array())
            fail("lights", "expected an array of lights, got " + typeOf(lights));
        if (lights.size() > 8) fail("lights", std::to_string(lights.size()) + " lights; at most 8");
        s.lights.clear();
        for (size_t i = 0; i < lights.size(); ++i) {
            LightSpec l;
            readLight(Object(lights[i], "lights[" + std::to_string(i) + "]"), l);
            s.lights.push_back(l);
        }
    }
    if (top.has("stage")) readStage(Object(top.raw("stage"), "stage"), s.stage);
    if (top.has("output")) readOutput(Object(top.raw("output"), "output"), s.output);
    if (!top.has("effects"))
        fail("effects", "missing; a scene lists its effects, e.g. {\"effects\": [{\"type\": "
                        "\"speed_lines\"}]}");
    const json& effects = top.raw("effects");
    if (!effects.is_array())
        fail("effects", "expected an array of effects, got " + typeOf(effects));
    if (effects.size() > 64)
        fail("effects", std::to_string(effects.size()) + " effects; at most 64");
    std::set<std::string> names;
    for (size_t i = 0; i < effects.size(); ++i) {
        EffectSpec e;
        const std::string path = "effects[" + std::to_string(i) + "]";
        readEffect(Object(effects[i], path), i, e);
        if (!names.insert(e.name).second)
            fail(path + ".name", "\"" + e.name + "\" is the name of an earlier effect");
        s.effects.push_back(e);
    }
    return s;
}

// nlohmann's message without its "[json.exception...]" prefix.
std::string parseMessage(const std::string& what) {
    const size_t close = what.find("] ");
    std::string m = close == std::string::npos ? what : what.substr(close + 2);
    if (m.rfind("parse error at ", 0) == 0) m = m.substr(15);
    return m;
}

} // namespace

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

Result<Scene> parseScene(const std::string& text, const std::string& where) {
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) { // syntax errors, and numbers too large for a double
        return Error{where + ": not valid JSON: " + parseMessage(e.what())};
    }
    try {
        return readScene(doc, where);
    } catch (const SceneError& e) {
        return Error{where + ": " + e.message};
    }
}

Result<Scene> loadScene(const std::filesystem::path& file) {
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
        return Error{file.string() + ": is a directory, not a scene file"};
    std::ifstream in(file, std::ios::binary);
    if (!in) return Error{file.string() + ": cannot read the scene file"};
    std::ostringstream text;
    text << in.rdbuf();
    if (text.str().size() > (64u << 20)) return Error{file.string() + ": larger than 64 MiB"};
    return parseScene(text.str(), file.string());
}

Scene defaultScene() {
    Scene s;
    s.file = "(built-in default scene)";
    s.camera.automatic = true;
    EffectSpec lines;
    lines.type = EffectType::SpeedLines;
    lines.name = "kick lines";
    lines.meshes = {"body"};
    lines.bones = {"shin_r", "foot_r", "toe_r"};
    lines.stride = 10;
    lines.lifetime = 12;
    lines.width = 0.02f;
    lines.colour = {1.0f, 0.85f, 0.3f, 1.0f};
    lines.useMeshColour = false;
    EffectSpec blur;
    blur.type = EffectType::MotionBlur;
    blur.name = "leg blur";
    blur.bones = {"thigh_r", "shin_r", "foot_r", "toe_r"};
    blur.lifetime = 6;
    blur.alphaStart = 0.55f;
    EffectSpec smoke;
    smoke.type = EffectType::Smoke;
    smoke.name = "foot smoke";
    smoke.bones = {"foot_r", "toe_r"};
    smoke.colour = {0.85f, 0.35f, 0.15f, 1.0f};
    smoke.useMeshColour = false;
    smoke.lifetime = 2;
    smoke.strength = 4.0f;
    smoke.radius = 0.08f;
    s.effects = {lines, blur, smoke};
    return s;
}

Scene previewScene(const std::string& file) {
    Scene s = defaultScene();
    s.file = "(preview of " + file + ")";
    s.character.source = file; // the preview's "file" is no folder: read from the working one
    s.effects[0].name = "speed lines";
    s.effects[1].name = "blur";
    s.effects[2].name = "smoke";
    for (EffectSpec& e : s.effects) {
        e.meshes.clear();
        e.bones.clear();
        e.automaticBones = true;
        e.automaticStride = true;
    }
    return s;
}

bool isCharacterFile(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension == ".gltf" || extension == ".glb";
}

Result<anim::Character> loadCharacter(const Scene& scene, std::string* note) {
    anim::Character character;
    if (scene.character.source == "fighter") {
        character = anim::makeFighter();
    } else {
        std::filesystem::path path(scene.character.source);
        if (path.is_relative() && !scene.file.empty() && scene.file[0] != '(')
            path = std::filesystem::path(scene.file).parent_path() / path;
        Result<anim::Character> imported = anim::importGltf(path);
        if (!imported) return Error{scene.file + ": character.source: " + imported.error().message};
        character = std::move(imported).value();
    }
    if (Status names = checkNames(scene, character); !names) return names.error();
    const std::string where =
        scene.character.source == "fighter"
            ? std::string("the built-in fighter")
            : std::filesystem::path(scene.character.source).filename().string();
    const float factor = chooseCharacterScale(scene, character, where, note);
    if (factor != 1.0f) anim::scaleCharacter(character, factor);
    return character;
}

Status checkClip(const Scene& scene, const anim::Character& character) {
    if (character.clips.empty())
        return Error{scene.file + ": character.source: \"" + scene.character.source +
                     "\" has no animation clip"};
    if (!scene.character.clip.empty() && !character.findClip(scene.character.clip)) {
        std::vector<std::string> clips;
        for (const anim::Clip& c : character.clips)
            clips.push_back(c.name);
        return Error{scene.file + ": character.clip: no clip \"" + scene.character.clip +
                     "\"; clips are: " + join(clips)};
    }
    const anim::Clip& clip = sceneClip(scene, character);
    if (scene.character.start >= clip.duration && clip.duration > 0.0f)
        return Error{scene.file + ": character.start: " + formatNumber(scene.character.start) +
                     " is not before the end of clip \"" + clip.name + "\" (" +
                     formatNumber(clip.duration) + " s)"};
    return Ok{};
}

Status checkNames(const Scene& scene, const anim::Character& character) {
    if (Status clip = checkClip(scene, character); !clip) return clip;
    for (size_t i = 0; i < scene.effects.size(); ++i) {
        const EffectSpec& e = scene.effects[i];
        const std::string path = "effects[" + std::to_string(i) + "]";
        for (size_t b = 0; b < e.bones.size(); ++b)
            if (auto bones = anim::resolveBoneEntry(character, e.bones[b]); !bones)
                return Error{scene.file + ": " + path + ".bones[" + std::to_string(b) +
                             "]: " + bones.error().message};
        for (size_t m = 0; m < e.meshes.size(); ++m)
            if (!character.findMesh(e.meshes[m])) {
                std::vector<std::string> meshes;
                for (const anim::Mesh& mesh : character.meshes)
                    meshes.push_back(mesh.name);
                return Error{scene.file + ": " + path + ".meshes[" + std::to_string(m) +
                             "]: no mesh \"" + e.meshes[m] + "\"; meshes are: " + join(meshes)};
            }
    }
    return Ok{};
}

const anim::Clip& sceneClip(const Scene& scene, const anim::Character& character) {
    if (!scene.character.clip.empty())
        if (const anim::Clip* c = character.findClip(scene.character.clip)) return *c;
    if (scene.character.source == "fighter")
        if (const anim::Clip* c = character.findClip("roundhouse_kick")) return *c;
    return character.clips.front();
}

float sceneDuration(const Scene& scene, const anim::Character& character) {
    const anim::Clip& clip = sceneClip(scene, character);
    const float end =
        scene.character.end ? std::min(*scene.character.end, clip.duration) : clip.duration;
    return std::max(end - scene.character.start, 0.0f) / scene.character.speed;
}

uint32_t frameCount(const Scene& scene, const anim::Character& character) {
    if (scene.output.frames) return *scene.output.frames;
    return std::max(1u, uint32_t(std::ceil(sceneDuration(scene, character) * scene.output.fps)));
}

float clipTimeAt(const Scene& scene, const anim::Character& character, float sceneTime) {
    const anim::Clip& clip = sceneClip(scene, character);
    const float start = scene.character.start;
    const float end =
        scene.character.end ? std::min(*scene.character.end, clip.duration) : clip.duration;
    const float span = std::max(end - start, 1e-6f);
    float t = sceneTime * scene.character.speed;
    if (scene.character.loop)
        t = std::fmod(std::max(t, 0.0f), span);
    else
        t = std::clamp(t, 0.0f, span);
    return start + t;
}

} // namespace mfx::scene
