#include "core/scene/scene.h"

#include "core/anim/bone_groups.h"
#include "core/anim/fighter.h"
#include "core/anim/gltf_import.h"
#include "core/json_shape.h"
#include "core/scene/default_scene_json.h"
#include "core/scene/effect_kinds.h"
#include "core/scene/json_object.h"
#include "core/scene/kinds/impact_effect.h"
#include "core/scene/kinds/smoke_effect.h"
#include "core/scene/kinds/trail_effects.h"
#include "core/scene/ribbon_texture.h"
#include "core/scene/scene_document.h"
#include "core/scene/scene_fit.h"
#include "core/scene/scene_params.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace mfx::scene {

namespace {

using namespace detail;

void readCharacter(const Object& o, CharacterSpec& c) {
    o.onlyKeys({"name", "source", "clip", "start", "end", "speed", "delay", "loop", "position",
                "yaw_degrees", "height", "scale", "style", "tint", "toon_bands", "rim",
                "outline_width", "outline_colour"});
    c.name = o.string("name", c.name);
    if (c.name.empty()) fail(o.at("name"), "must not be empty");
    c.source = o.string("source", c.source);
    if (c.source.empty()) fail(o.at("source"), "must name \"fighter\" or a .gltf/.glb file");
    c.clip = o.string("clip", c.clip);
    c.start = float(o.number("start", c.start, 0.0, 1e5));
    c.end = o.optionalNumber("end", 0.0, 1e5);
    if (c.end && *c.end <= c.start)
        fail(o.at("end"),
             formatNumber(*c.end) + " is not after start (" + formatNumber(c.start) + ")");
    c.speed = float(o.number("speed", c.speed, 0.0, 100.0, true));
    c.delay = float(o.number("delay", c.delay, 0.0, 1e4));
    c.loop = o.boolean("loop", c.loop);
    c.position = o.vec3("position", c.position);
    c.yawDegrees = float(o.number("yaw_degrees", c.yawDegrees, -3600.0, 3600.0));
    if (o.given("height") && o.given("scale"))
        fail(o.at("scale"), "give height or scale, not both (height: the metres to scale the "
                            "character to; scale: the factor to scale it by)");
    if (const std::optional<double> h = o.optionalNumber("height", 1e-4, 1e4)) c.height = *h;
    if (const std::optional<double> f = o.optionalNumber("scale", 1e-6, 1e6)) c.scale = *f;
    if (o.has("style"))
        c.style = o.choice("style", "", {"toon", "lit"}) == "toon" ? CharacterStyle::Toon
                                                                   : CharacterStyle::Lit;
    c.tint = glm::vec3(o.colour("tint", glm::vec4(c.tint, 1.0f)));
    c.toonBands = o.integer("toon_bands", c.toonBands, 2, 4);
    c.rim = float(o.number("rim", c.rim, 0.0, 4.0));
    c.outlineWidth = float(o.number("outline_width", c.outlineWidth, 0.0, 16.0));
    c.outlineColour = glm::vec3(o.colour("outline_colour", glm::vec4(c.outlineColour, 1.0f)));
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
    if (o.has("frames") && !o.null("frames")) out.frames = o.integer("frames", 1, 1, kMaxFrames);
}

void readPost(const Object& o, PostSpec& post) {
    o.onlyKeys({"exposure", "bloom", "tone_map"});
    post.exposure = float(o.number("exposure", post.exposure, -16.0, 16.0));
    post.bloom = float(o.number("bloom", post.bloom, 0.0, 1.0));
    const std::string toneMap =
        o.choice("tone_map", post.toneMap == ToneMap::Aces ? "aces" : "none", {"aces", "none"});
    post.toneMap = toneMap == "aces" ? ToneMap::Aces : ToneMap::None;
}

// An impact's target is another character of the scene.
void checkImpact(const Scene& s, size_t i, const ImpactSpec& impact) {
    const std::string path = "effects[" + std::to_string(i) + "]";
    std::vector<std::string> cast;
    for (const CharacterSpec& c : s.characters)
        cast.push_back(c.name);
    const std::string& attacker = s.characters[effectCharacter(s, s.effects[i])].name;
    if (!impact.target.empty()) {
        if (std::find(cast.begin(), cast.end(), impact.target) == cast.end())
            fail(path + ".target",
                 "no character \"" + impact.target + "\"; characters are: " + join(cast));
        if (impact.target == attacker)
            fail(path + ".target", "\"" + impact.target +
                                       "\" is the character the impact follows; a blow lands "
                                       "on another");
    }
}

Scene readScene(const json& doc, const std::string& where) {
    Scene s;
    s.file = where;
    const Object top(doc, "");
    top.onlyKeys(
        {"character", "characters", "camera", "lights", "stage", "output", "post", "effects"});
    if (top.has("character") && top.has("characters"))
        fail("characters", "give \"character\" (one) or \"characters\" (a list), not both");
    if (top.has("character"))
        readCharacter(Object(top.raw("character"), "character"), s.characters.front());
    if (top.has("characters")) {
        const json& list = top.raw("characters");
        if (!list.is_array())
            fail("characters", "expected an array of characters, got " + typeOf(list));
        if (list.empty() || list.size() > kMaxCharacters)
            fail("characters", std::to_string(list.size()) + " characters; 1 to " +
                                   std::to_string(kMaxCharacters));
        s.characters.clear();
        for (size_t i = 0; i < list.size(); ++i) {
            const std::string path = "characters[" + std::to_string(i) + "]";
            CharacterSpec c;
            c.name = "p" + std::to_string(i + 1);
            readCharacter(Object(list[i], path), c);
            for (size_t j = 0; j < i; ++j)
                if (s.characters[j].name == c.name)
                    fail(path + ".name", "\"" + c.name + "\" is the name of characters[" +
                                             std::to_string(j) + "]; give each a name of its own");
            s.characters.push_back(c);
        }
    }
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
    if (top.has("post")) readPost(Object(top.raw("post"), "post"), s.post);
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
        const std::string path = "effects[" + std::to_string(i) + "]";
        EffectSpec e = readEffect(Object(effects[i], path), i);
        if (!names.insert(e.name).second)
            fail(path + ".name", "\"" + e.name + "\" is the name of an earlier effect");
        if (!e.character.empty() &&
            std::none_of(s.characters.begin(), s.characters.end(),
                         [&](const CharacterSpec& c) { return c.name == e.character; })) {
            std::vector<std::string> cast;
            for (const CharacterSpec& c : s.characters)
                cast.push_back(c.name);
            fail(path + ".character",
                 "no character \"" + e.character + "\"; characters are: " + join(cast));
        }
        s.effects.push_back(e);
    }
    for (size_t i = 0; i < s.effects.size(); ++i)
        if (const ImpactSpec* impact = s.effects[i].as<ImpactSpec>()) checkImpact(s, i, *impact);
    return s;
}

// A scene file nests six levels at most (effects[i].colour_over_life[j].colour) and holds a few
// hundred values; these bounds leave room for any hand-written or generated scene.
constexpr JsonLimits kSceneJsonLimits{32, size_t(1) << 16};

// nlohmann's message without its "[json.exception...]" prefix.
std::string parseMessage(const std::string& what) {
    const size_t close = what.find("] ");
    std::string m = close == std::string::npos ? what : what.substr(close + 2);
    if (m.rfind("parse error at ", 0) == 0) m = m.substr(15);
    return m;
}

// Where playback ends in the clip: character.end, at most the clip's end.
float clipEnd(const CharacterSpec& spec, const anim::Clip& clip) {
    return spec.end ? std::min(*spec.end, clip.duration) : clip.duration;
}

// The frames a clip lasts at its speed and the scene's fps, rounded up, in float as frameCount
// has always counted them (a slow speed or a long clip can make it any size, infinity included).
float unboundedFrames(const Scene& scene, const CharacterSpec& spec,
                      const anim::Character& character) {
    return std::ceil(characterDuration(spec, character) * scene.output.fps);
}

// "character" for a scene of one character, else "characters[c]": where errors point.
std::string characterPath(const Scene& scene, size_t c) {
    return scene.characters.size() == 1 ? std::string("character")
                                        : "characters[" + std::to_string(c) + "]";
}

} // namespace

const std::vector<std::string>& sceneSections() {
    static const std::vector<std::string> sections = {"character", "camera", "lights",
                                                      "stage",     "output", "post"};
    return sections;
}

std::vector<ParamInfo> sectionParams(const std::string& section) {
    Description described;
    const Object o(described);
    if (section == "character") {
        CharacterSpec c;
        readCharacter(o, c);
    } else if (section == "camera") {
        CameraSpec c;
        readCamera(o, c);
    } else if (section == "lights") {
        LightSpec l;
        readLight(o, l);
    } else if (section == "stage") {
        StageSpec s;
        readStage(o, s);
    } else if (section == "output") {
        OutputSpec out;
        readOutput(o, out);
    } else if (section == "post") {
        PostSpec post;
        readPost(o, post);
    } else {
        throw std::invalid_argument("no scene section \"" + section + "\"");
    }
    return uniqueParams(described);
}

const ParamInfo* findParam(const std::vector<ParamInfo>& params, const std::string& key) {
    for (const ParamInfo& p : params)
        if (p.key == key) return &p;
    return nullptr;
}

CharacterStyle characterStyle(const CharacterSpec& character) {
    if (character.style) return *character.style;
    return character.source == "fighter" ? CharacterStyle::Toon : CharacterStyle::Lit;
}

Result<json> parseSceneJson(const std::string& text, const std::string& where) {
    // Bounded before parsing: the readers (and nlohmann's copies) recurse once per level.
    if (Status shape = checkJsonShape(text, kSceneJsonLimits); !shape)
        return Error{where + ": " + shape.error().message};
    try {
        return json::parse(text);
    } catch (const json::exception& e) { // syntax errors, and numbers too large for a double
        return Error{where + ": not valid JSON: " + parseMessage(e.what())};
    }
}

Result<Scene> sceneFromJson(const json& doc, const std::string& where) {
    try {
        return readScene(doc, where);
    } catch (const SceneError& e) {
        return Error{where + ": " + e.message};
    }
}

Result<Scene> parseScene(const std::string& text, const std::string& where) {
    Result<json> doc = parseSceneJson(text, where);
    if (!doc) return doc.error();
    return sceneFromJson(doc.value(), where);
}

Result<std::string> readSceneText(const std::filesystem::path& file) {
    constexpr size_t kMaxBytes = size_t(64) << 20;
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
        return Error{file.string() + ": is a directory, not a scene file"};
    // A device or a pipe (/dev/zero, a FIFO) would be read for ever: regular files only, their
    // size checked before reading, and the read itself bounded (a file may grow meanwhile).
    if (std::filesystem::exists(file, ec) && !std::filesystem::is_regular_file(file, ec))
        return Error{file.string() + ": not a regular file"};
    if (const uintmax_t size = std::filesystem::file_size(file, ec); !ec && size > kMaxBytes)
        return Error{file.string() + ": larger than 64 MiB"};
    std::ifstream in(file, std::ios::binary);
    if (!in) return Error{file.string() + ": cannot read the scene file"};
    std::string text;
    std::vector<char> chunk(size_t(1) << 16);
    while (in.read(chunk.data(), std::streamsize(chunk.size())) || in.gcount() > 0) {
        text.append(chunk.data(), size_t(in.gcount()));
        if (text.size() > kMaxBytes) return Error{file.string() + ": larger than 64 MiB"};
    }
    return text;
}

Result<Scene> loadScene(const std::filesystem::path& file) {
    Result<std::string> text = readSceneText(file);
    if (!text) return text.error();
    Result<Scene> scene = parseScene(text.value(), file.string());
    if (!scene) return scene;
    if (Status textures = checkTextures(scene.value()); !textures) return textures.error();
    return scene;
}

Scene kickScene() {
    Scene s;
    s.file = "(built-in kick scene)";
    s.camera.automatic = true;
    SpeedLinesSpec lines;
    lines.trail.stride = 10;
    lines.trail.lifetime = 12;
    lines.width = 0.02f;
    EffectSpec kickLines(lines, "kick lines");
    kickLines.meshes = {"body"};
    kickLines.bones = {"shin_r", "foot_r", "toe_r"};
    EffectSpec blur(MotionBlurSpec{}, "leg blur"); // lifetime 6, alpha from 0.55
    blur.bones = {"thigh_r", "shin_r", "foot_r", "toe_r"};
    SmokeSpec smoke;
    smoke.strength = 4.0f;
    smoke.radius = 0.08f;
    EffectSpec footSmoke(smoke, "foot smoke");
    footSmoke.bones = {"foot_r", "toe_r"};
    s.effects = {kickLines, blur, footSmoke};
    return s;
}

std::string defaultSceneJson() {
    return kDefaultSceneJson;
}

Scene defaultScene() {
    // docs/scenes/hero.json, embedded at build time; a test keeps it parsing.
    Result<Scene> s =
        parseScene(kDefaultSceneJson, "(built-in default scene: docs/scenes/hero.json)");
    if (!s) throw std::logic_error(s.error().message);
    return std::move(s).value();
}

Scene previewScene(const std::string& file) {
    Scene s = kickScene();
    s.file = "(preview of " + file + ")";
    s.characters.front().source =
        file; // the preview's "file" is no folder: read from the working one
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

size_t effectCharacter(const Scene& scene, const EffectSpec& e) {
    for (size_t c = 0; c < scene.characters.size(); ++c)
        if (scene.characters[c].name == e.character) return c;
    return 0;
}

std::filesystem::path characterFile(const Scene& scene, const CharacterSpec& character) {
    if (character.source == "fighter") return {};
    std::filesystem::path path(character.source);
    if (path.is_relative() && !scene.file.empty() && scene.file[0] != '(')
        path = std::filesystem::path(scene.file).parent_path() / path;
    return path;
}

Result<anim::Character> loadCharacter(const Scene& scene, size_t c, std::string* note) {
    if (c >= scene.characters.size())
        return Error{scene.file + ": no character " + std::to_string(c) + " (the scene has " +
                     std::to_string(scene.characters.size()) + ")"};
    const CharacterSpec& spec = scene.characters[c];
    anim::Character character;
    if (spec.source == "fighter") {
        character = anim::makeFighter();
    } else {
        Result<anim::Character> imported = anim::importGltf(characterFile(scene, spec));
        if (!imported)
            return Error{scene.file + ": " + characterPath(scene, c) +
                         ".source: " + imported.error().message};
        character = std::move(imported).value();
    }
    if (Status names = checkNames(scene, c, character); !names) return names.error();
    const std::string where = spec.source == "fighter"
                                  ? std::string("the built-in fighter")
                                  : std::filesystem::path(spec.source).filename().string();
    const float factor = chooseCharacterScale(scene, c, character, where, note);
    if (factor != 1.0f) anim::scaleCharacter(character, factor);
    return character;
}

Result<Cast> loadCast(const Scene& scene, std::vector<std::string>* notes) {
    Cast cast;
    for (size_t c = 0; c < scene.characters.size(); ++c) {
        std::string note;
        Result<anim::Character> character = loadCharacter(scene, c, &note);
        if (!character) return character.error();
        cast.push_back(std::move(character).value());
        if (notes && !note.empty()) notes->push_back(note);
    }
    return cast;
}

Status checkClip(const Scene& scene, size_t c, const anim::Character& character) {
    const CharacterSpec& spec = scene.characters.at(c);
    const std::string path = scene.file + ": " + characterPath(scene, c);
    if (character.clips.empty())
        return Error{path + ".source: \"" + spec.source + "\" has no animation clip"};
    if (!spec.clip.empty() && !character.findClip(spec.clip)) {
        std::vector<std::string> clips;
        for (const anim::Clip& clip : character.clips)
            clips.push_back(clip.name);
        return Error{path + ".clip: no clip \"" + spec.clip + "\"; clips are: " + join(clips)};
    }
    const anim::Clip& clip = sceneClip(spec, character);
    if (spec.start >= clip.duration && clip.duration > 0.0f)
        return Error{path + ".start: " + formatNumber(spec.start) +
                     " is not before the end of clip \"" + clip.name + "\" (" +
                     formatNumber(clip.duration) + " s)"};
    if (!scene.output.frames) {
        const float frames = unboundedFrames(scene, spec, character);
        if (!(frames <= float(kMaxFrames)))
            return Error{path + ".speed: clip \"" + clip.name + "\" from " +
                         formatNumber(spec.start) + " s to " + formatNumber(clipEnd(spec, clip)) +
                         " s at speed " + formatNumber(spec.speed) + " lasts " +
                         formatNumber(double(frames)) + " frames at " +
                         formatNumber(scene.output.fps) + " fps; at most " +
                         std::to_string(kMaxFrames) +
                         " (give a faster speed, an earlier end or output.frames)"};
    }
    return Ok{};
}

Status checkNames(const Scene& scene, size_t c, const anim::Character& character) {
    if (Status clip = checkClip(scene, c, character); !clip) return clip;
    for (size_t i = 0; i < scene.effects.size(); ++i) {
        const EffectSpec& e = scene.effects[i];
        if (effectCharacter(scene, e) != c) continue;
        const std::string path = "effects[" + std::to_string(i) + "]";
        for (size_t b = 0; b < e.bones.size(); ++b)
            if (auto bones = anim::resolveBoneEntry(character, e.bones[b]); !bones)
                return Error{scene.file + ": " + path + ".bones[" + std::to_string(b) +
                             "]: " + bones.error().message};
        if (const SmokeSpec* smoke = e.as<SmokeSpec>())
            for (size_t b = 0; b < smoke->grid.collideBones.size(); ++b)
                if (auto bones = anim::resolveBoneEntry(character, smoke->grid.collideBones[b]);
                    !bones)
                    return Error{scene.file + ": " + path + ".collide_bones[" + std::to_string(b) +
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

Status checkNames(const Scene& scene, std::span<const anim::Character> cast) {
    if (cast.size() != scene.characters.size())
        return Error{scene.file + ": " + std::to_string(cast.size()) + " characters loaded for " +
                     std::to_string(scene.characters.size()) + " in the scene"};
    for (size_t c = 0; c < cast.size(); ++c)
        if (Status names = checkNames(scene, c, cast[c]); !names) return names;
    return Ok{};
}

const anim::Clip& sceneClip(const CharacterSpec& spec, const anim::Character& character) {
    if (!spec.clip.empty())
        if (const anim::Clip* c = character.findClip(spec.clip)) return *c;
    if (spec.source == "fighter")
        if (const anim::Clip* c = character.findClip("roundhouse_kick")) return *c;
    return character.clips.front();
}

float characterDuration(const CharacterSpec& spec, const anim::Character& character) {
    const anim::Clip& clip = sceneClip(spec, character);
    return spec.delay + std::max(clipEnd(spec, clip) - spec.start, 0.0f) / spec.speed;
}

float sceneDuration(const Scene& scene, std::span<const anim::Character> cast) {
    float longest = 0.0f;
    for (size_t c = 0; c < cast.size() && c < scene.characters.size(); ++c)
        longest = std::max(longest, characterDuration(scene.characters[c], cast[c]));
    return longest;
}

float performanceTime(const Scene& scene, float sceneTime) {
    float t = sceneTime;
    for (const Hit& hit : scene.hits) {
        const float start = float(hit.frame) / scene.output.fps;
        if (sceneTime > start)
            t -= std::min(sceneTime - start, float(hit.holdFrames) / scene.output.fps);
    }
    return t;
}

uint32_t frameCount(const Scene& scene, std::span<const anim::Character> cast) {
    if (scene.output.frames) return *scene.output.frames;
    float held = 0.0f;
    for (const Hit& hit : scene.hits)
        held += float(hit.holdFrames);
    const float frames = std::ceil(sceneDuration(scene, cast) * scene.output.fps) + held;
    return frames <= float(kMaxFrames) ? std::max(1u, uint32_t(frames)) : kMaxFrames;
}

float clipTimeAt(const CharacterSpec& spec, const anim::Character& character, float sceneTime) {
    const anim::Clip& clip = sceneClip(spec, character);
    const float start = spec.start;
    const float end = clipEnd(spec, clip);
    const float span = std::max(end - start, 1e-6f);
    float t = std::max(sceneTime - spec.delay, 0.0f) * spec.speed;
    if (spec.loop)
        t = std::fmod(std::max(t, 0.0f), span);
    else
        t = std::clamp(t, 0.0f, span);
    return start + t;
}

} // namespace mfx::scene
