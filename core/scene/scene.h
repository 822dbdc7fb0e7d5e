// The scene file: which character moves how, what the camera and lights are, what is rendered,
// and which effects are bound to which bones and meshes, when. JSON, every key optional but
// "effects"; unknown keys, wrong types, out-of-range values and unknown names are refused with one
// error naming the key path (e.g. `effects[2].bones[0]: no bone "hand_X"; bones are: ...`).
// README.md "Scene files" documents every key with a complete example; defaults are below.
#pragma once

#include "core/anim/character.h"
#include "core/result.h"
#include "core/scene/effect_spec.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace mfx::scene {

// How the character is shaded (render/character_pass.h).
enum class CharacterStyle {
    Lit,  // Blinn-Phong with a hemisphere ambient
    Toon, // banded diffuse from a ramp, a rim light and inverted-hull outlines
};

struct CharacterSpec {
    // What effects name it by ("character" of an effect); default "p1", "p2", ... by its place.
    std::string name = "p1";
    std::string source = "fighter"; // "fighter" (built in) or a .gltf/.glb path
    std::string clip;               // empty: roundhouse_kick for the fighter, else the first
    float start = 0.0f;             // clip seconds where playback starts
    std::optional<float> end;       // clip seconds where it ends (default: the clip's end)
    float speed = 1.0f;             // playback speed
    // Scene seconds before the clip starts playing (it holds its first pose until then): a
    // fighter's reaction timed to the blow that lands on it.
    float delay = 0.0f;
    bool loop = false;        // past `end`, wrap to `start` (else hold the last pose)
    glm::vec3 position{0.0f}; // world placement
    float yawDegrees = 0.0f;  // rotation about +y
    // Size (scene_fit.h): the height in metres to scale the character to, or the factor to scale
    // it by; neither: outliers are brought to a human height, others left alone.
    std::optional<float> height;
    std::optional<float> scale;
    // Shading: default toon for the built-in fighter, lit for a character file (characterStyle).
    std::optional<CharacterStyle> style;
    // Multiplies the colours of its materials (linear RGB): two of the same fighter told apart.
    glm::vec3 tint{1.0f};
    uint32_t toonBands = 3;    // levels of the diffuse ramp, 2-4
    float rim = 0.6f;          // strength of the toon rim light, 0: none
    float outlineWidth = 2.0f; // toon outline width in pixels of the output, 0: none
    glm::vec3 outlineColour{0.02f, 0.015f, 0.03f}; // linear
};

// The character's style: its "style", else toon for the built-in fighter and lit for a file.
CharacterStyle characterStyle(const CharacterSpec& character);

struct CameraSpec {
    glm::vec3 position{2.6f, 1.5f, 3.4f};
    glm::vec3 target{0.0f, 0.95f, 0.0f};
    float fovDegrees = 40.0f; // vertical
    float nearPlane = 0.05f;
    float farPlane = 50.0f;
    // Set where the scene has no "camera": fitScene frames the character (and sizes the stage).
    bool automatic = false;
};

struct LightSpec {
    glm::vec3 direction{-0.4f, -1.0f, -0.35f}; // the way the light travels
    glm::vec3 colour{1.0f, 0.97f, 0.9f};
    float intensity = 1.0f;
    bool shadow = true;
};

struct StageSpec {
    bool floor = true;
    bool backdrop = true;
    glm::vec3 floorColour{0.32f, 0.30f, 0.36f};
    glm::vec3 backdropColour{0.12f, 0.13f, 0.2f};
    // Where the stage stands (not keys of the scene file: fitScene sizes them to the character
    // when it frames the camera; these defaults suit a 1.8 m character at the origin).
    float floorHeight = 0.0f;
    glm::vec3 floorCentre{0.0f}; // x and z; y is floorHeight
    float floorHalfSize = 40.0f; // the floor is a square 2x this across
    glm::vec3 backdropCentre{0.0f, 10.0f, -4.0f};
    glm::vec3 backdropHalfWidth{40.0f, 0.0f, 0.0f}; // horizontal, along the backdrop
    float backdropHalfHeight = 10.0f;
    std::optional<glm::vec3> shadowCentre; // default: the first character's position + (0, 1, 0)
    float shadowRadius = 2.5f;             // half-size of the key light's shadow box
};

struct OutputSpec {
    uint32_t width = 1280;
    uint32_t height = 720;
    float fps = 30.0f;
    std::optional<uint32_t> frames; // default: the playback range at fps
};

// What happens to the picture after it is drawn in linear HDR colour, before its 8-bit output
// (render/bloom_pass.h, render/tone_map_pass.h). Each stage has a value that turns it off, and
// with all three off the output is the drawn colour clamped to [0, 1].
enum class ToneMap {
    None, // clamp to [0, 1]
    Aces, // the ACES filmic curve (K. Narkowicz's fit of the RRT and ODT), per channel
};
// On by default (a little bloom and the filmic curve), as a renderer's picture is; "bloom": 0 and
// "tone_map": "none" turn them off.
struct PostSpec {
    float exposure = 0.0f;           // stops: the picture is scaled by 2^exposure (0: unchanged)
    float bloom = 0.1f;              // share of the blurred picture in the result (0: no bloom)
    ToneMap toneMap = ToneMap::Aces; // None: no tone map (a clamp)
};

// The most characters a scene has ("characters"; the single "character" is one).
constexpr size_t kMaxCharacters = 4;

// Where an impact effect's blow lands on another character (core/scene/scene_hits.h: found by
// fitScene, not a key of the scene file).
struct Hit {
    size_t effect = 0;     // the impact, in scene.effects
    size_t attacker = 0;   // the character it follows, in scene.characters
    size_t target = 0;     // the character struck
    uint32_t frame = 0;    // the scene frame it lands in: time in ((frame - 1) / fps, frame / fps]
    float time = 0.0f;     // scene seconds
    glm::vec3 point{0.0f}; // world: on the attacker's surface where it touches
    glm::vec3 direction{0.0f}; // of the blow: the attacker's point relative to the target's
    float speed = 0.0f;        // m/s
    std::string attackerBone, targetBone;
    uint32_t holdFrames = 0; // hit-stop: frames frame + 1 .. frame + holdFrames hold the clips
};

struct Scene {
    std::string file; // where it came from ("(built-in default)" for the default scene)
    // Never empty: "character" gives one, "characters" one to kMaxCharacters (names unique).
    std::vector<CharacterSpec> characters{CharacterSpec{}};
    CameraSpec camera;
    std::vector<LightSpec> lights{LightSpec{}};
    StageSpec stage;
    OutputSpec output;
    PostSpec post;
    std::vector<EffectSpec> effects;
    // The impacts' hits in time order, set once by fitScene (hitsFound) when the scene has an
    // impact; their hit-stops hold every character's clip (characterPose, frameCount).
    std::vector<Hit> hits;
    bool hitsFound = false;
};

// Parses and checks a scene's JSON text; `where` names it in errors (a file name).
Result<Scene> parseScene(const std::string& text, const std::string& where);
// Reads and parses a scene file.
Result<Scene> loadScene(const std::filesystem::path& file);
// A scene file's text (refusing a folder, an unreadable file, or one over 64 MiB).
Result<std::string> readSceneText(const std::filesystem::path& file);
// The built-in default (docs/scenes/hero.json): the fighter's roundhouse kick into the sword
// slash, toon-shaded, with glowing kick lines, a crescent slash arc on the sword, energy smoke
// from the kicking foot, bloom and the filmic tone map.
Scene defaultScene();
// Its text (docs/scenes/hero.json as built in).
std::string defaultSceneJson();
// The plain kick: the fighter's roundhouse kick with speed-lines, a blur volume on the kicking
// leg and smoke from the kicking foot (what the tests and the character preview build on).
Scene kickScene();

// What `motionfx render CHARACTER.glb` plays: the file's first clip (or character.clip, once
// set), framed by fitScene, with the kick scene's speed-lines, blur volume and smoke bound to
// the fastest limb at automatic strides. `file` is named as given (relative to the working
// directory).
Scene previewScene(const std::string& file);
// Whether a command's first word names a character file (.gltf or .glb) rather than a scene.
bool isCharacterFile(const std::string& path);

// The scene's characters, loaded, in the order of scene.characters (what the simulation, the
// fitting and the renderers are given).
using Cast = std::vector<anim::Character>;

// The index in scene.characters of the character effect `e` follows (its "character"; the first
// when it names none). The reader has checked the name.
size_t effectCharacter(const Scene& scene, const EffectSpec& e);

// Loads character `c` of the scene (the built-in fighter or a glTF file relative to the scene
// file's folder), scales it to a sane size (scene_fit.h: chooseCharacterScale; `note`, when not
// null, gets the line saying so) and checks its clip and the bone and mesh names of the effects
// that follow it (checkNames).
Result<anim::Character> loadCharacter(const Scene& scene, size_t c = 0,
                                      std::string* note = nullptr);
// Every character of the scene (loadCharacter); `notes` gets the non-empty notes.
Result<Cast> loadCast(const Scene& scene, std::vector<std::string>* notes = nullptr);
// The file loadCharacter reads for `character` (relative paths against the scene file's folder);
// empty for the built-in fighter.
std::filesystem::path characterFile(const Scene& scene, const CharacterSpec& character);
// Checks that character `c` has its clip, that playback starts inside it, and that the frames it
// lasts (without output.frames) are at most kMaxFrames.
Status checkClip(const Scene& scene, size_t c, const anim::Character& character);
// checkClip, then the bone (plain names, groups and patterns) and mesh names of every effect that
// follows character `c`.
Status checkNames(const Scene& scene, size_t c, const anim::Character& character);
// checkNames for every character; the cast must have one character per scene.characters entry.
Status checkNames(const Scene& scene, std::span<const anim::Character> cast);
inline Status checkNames(const Scene& scene, const anim::Character& character) {
    return checkNames(scene, std::span<const anim::Character>(&character, 1));
}

// The most frames a scene renders (output.frames, or its clip's length at its speed and fps): every
// per-frame loop over a scene is bounded by it. checkClip refuses a scene whose clip runs longer.
constexpr uint32_t kMaxFrames = 100000;

// Seconds of scene time a character's clip plays for (from start to end at its speed), and the
// clip time at a scene time.
float characterDuration(const CharacterSpec& spec, const anim::Character& character);
float clipTimeAt(const CharacterSpec& spec, const anim::Character& character, float sceneTime);
const anim::Clip& sceneClip(const CharacterSpec& spec, const anim::Character& character);
// The performance's time at scene time `sceneTime`: the scene time less the hit-stops (scene.hits)
// before it; it stands still while one lasts. Every character's clip plays at it.
float performanceTime(const Scene& scene, float sceneTime);
// Seconds of scene time the output covers: the longest character's (without hit-stops).
float sceneDuration(const Scene& scene, std::span<const anim::Character> cast);
inline float sceneDuration(const Scene& scene, const anim::Character& character) {
    return sceneDuration(scene, std::span<const anim::Character>(&character, 1));
}
// The frames the output has: output.frames, else the duration at the scene's fps and the
// hit-stops' frames, at most kMaxFrames (checkClip has refused a longer clip; the bound keeps
// this defined regardless).
uint32_t frameCount(const Scene& scene, std::span<const anim::Character> cast);
inline uint32_t frameCount(const Scene& scene, const anim::Character& character) {
    return frameCount(scene, std::span<const anim::Character>(&character, 1));
}

} // namespace mfx::scene
