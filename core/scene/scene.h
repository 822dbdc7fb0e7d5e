// The scene file: which character moves how, what the camera and lights are, what is rendered,
// and which effects are bound to which bones and meshes, when. JSON, every key optional but
// "effects"; unknown keys, wrong types, out-of-range values and unknown names are refused with one
// error naming the key path (e.g. `effects[2].bones[0]: no bone "hand_X"; bones are: ...`).
// README.md "Scene files" documents every key with a complete example; defaults are below.
#pragma once

#include "core/anim/character.h"
#include "core/result.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace mfx::scene {

struct CharacterSpec {
    std::string source = "fighter"; // "fighter" (built in) or a .gltf/.glb path
    std::string clip;               // empty: roundhouse_kick for the fighter, else the first
    float start = 0.0f;             // clip seconds where playback starts
    std::optional<float> end;       // clip seconds where it ends (default: the clip's end)
    float speed = 1.0f;             // playback speed
    bool loop = false;              // past `end`, wrap to `start` (else hold the last pose)
    glm::vec3 position{0.0f};       // world placement
    float yawDegrees = 0.0f;        // rotation about +y
    // Size (scene_fit.h): the height in metres to scale the character to, or the factor to scale
    // it by; neither: outliers are brought to a human height, others left alone.
    std::optional<float> height;
    std::optional<float> scale;
};

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
    std::optional<glm::vec3> shadowCentre; // default: character.position + (0, 1, 0)
    float shadowRadius = 2.5f;             // half-size of the key light's shadow box
};

struct OutputSpec {
    uint32_t width = 1280;
    uint32_t height = 720;
    float fps = 30.0f;
    std::optional<uint32_t> frames; // default: the playback range at fps
};

enum class EffectType {
    SpeedLines,
    MotionBlur,
    MotionParticles,
    Smoke,
    AfterimageSmear,
    SweptVolume,
    SilhouetteShell
};
enum class Emission { Vertices, Surface };

// Afterimage toon blur (Smith 2016, chapters 4 and 5): what is drawn from the rear-facing
// vertices pushed back along their motion.
enum class AfterimageVariant {
    Smear,      // the bound mesh, its rear vertices moved (single afterimage, Sec. 4.1)
    SpeedLines, // a line from each rear vertex to where it would be pushed (Sec. 4.3)
    Multi,      // arcs through the recorded history (multi-afterimage, Sec. 5.1)
};

// The options of an afterimage_smear effect (Smith 2016, Sec. 4.3 and 5.3).
struct AfterimageSpec {
    AfterimageVariant variant = AfterimageVariant::Smear;
    float strengthCharacter = 1.0f; // f^U: push per frame of the whole character's travel
    float strengthAnimation = 2.0f; // f^V: push per frame of the animation's own motion
    float randomMin = 0.0f;         // the per-vertex random value R lies in [min, max] ...
    float randomMax = 1.0f;
    float randomThreshold = 0.0f; // ... and is 0 below this (a sharper, more jagged smear)
    float taper = 0.0f;           // push scaled by (-cos(normal, motion))^taper; 0: none
    float minSpeed = 0.0f;        // world units per second a vertex must move to smear
    float relativeSpeed = 0.0f;   // fraction of the fastest bound vertex's speed it must reach
    uint32_t afterimages = 5;     // multi: recorded positions an arc runs through
    float influencePower = 0.0f;  // multi: k of (1 - (1 - D/Dmax) j/n)^k (Sec. 5.3 b); 0: none
};

// The temporal filter whose weight over the exposure shapes a swept volume's alpha (Wloka and
// Zeleznik 1996, Sec. 3.4).
enum class SweptFilter { Box, Ramp, Triangle, Gaussian };

// The options of a swept_volume effect (Wloka and Zeleznik 1996, Sec. 3.4 and 4.2). Its colour is
// EffectSpec::colour (default the mesh's); EffectSpec::subSamples is the quads per segment.
struct SweptVolumeSpec {
    SweptFilter filter = SweptFilter::Ramp;
    uint32_t segments = 1;   // n: recorded frames the sweep runs back through, one a segment
    float alphaFloor = 0.1f; // the least alpha anywhere on the volume (the paper's 0.1)
};

// Which edge of a polygon lies on the silhouette of motion (Jones 2004, Sec. 3.2.4): the one
// between its two vertices facing away from their motion (the paper's figure), or between the two
// facing it.
enum class ShellEdgeRule { Back, Front };

// The options of a silhouette_shell effect (Jones 2004, Sec. 3.2.2 and 3.3). Its colour is
// EffectSpec::colour (default the mesh's).
struct SilhouetteShellSpec {
    uint32_t subdivisions = 6;     // silhouettes kept per polygon: quads in a full strip
    std::optional<float> blurTime; // seconds the shell spans; default subdivisions / fps
    float initialAlpha = 0.8f;     // alpha of each strip at the live mesh, falling to 0
    uint32_t fadeOut = 3;          // updates a polygon off the silhouette fades its strip over
    ShellEdgeRule edgeRule = ShellEdgeRule::Back;
};

struct EffectSpec {
    EffectType type = EffectType::SpeedLines;
    std::string name;                // default: type and index, e.g. "speed_lines#0"
    std::vector<std::string> bones;  // empty: the whole character
    std::vector<std::string> meshes; // empty: every mesh
    float minBoneWeight = 0.5f;
    // Set by the parser where the effect has neither "bones" nor "meshes" (fitScene binds it to
    // the fastest limb) and where it has no "stride" (fitScene chooses one from the vertex count).
    bool automaticBones = false;
    bool automaticStride = false;
    // The keys the scene file gave this effect (fitScene scales the length defaults of the others
    // to a character sized outside the human range on purpose).
    std::vector<std::string> givenKeys;
    bool given(const std::string& key) const {
        return std::find(givenKeys.begin(), givenKeys.end(), key) != givenKeys.end();
    }
    float start = 0.0f;       // the window, in scene seconds
    std::optional<float> end; // default: the end of the scene
    // Trajectory (speed lines, blur volumes, particles; smoke reads its segments too).
    uint32_t subSamples = 4;
    uint32_t lifetime = 12; // frames
    uint32_t stride = 1;    // every n-th source vertex (speed lines look best sparse)
    glm::vec4 colour{1.0f}; // RGBA; the mesh colour when "colour" is absent (blur)
    bool useMeshColour = true;
    float alphaStart = 1.0f;
    float alphaEnd = 0.0f;
    float alphaPower = 1.0f;
    float width = 0.012f; // speed-line ribbon width (world units)
    float size = 0.02f;   // particle size (world units)
    // Smoke.
    std::array<uint32_t, 3> grid{48, 48, 48};
    float cellSize = 0.05f;
    uint32_t jacobi = 20;
    float fade = 0.6f;            // pigment decay per second
    float drag = 1.0f;            // velocity decay per second
    float stepsPerSecond = 60.0f; // solver steps per second at least (whole steps per frame)
    bool follow = false;          // the grid moves with the character's root, by whole cells
    float buoyancy = 0.0f;
    float vorticity = 0.0f;
    float impulseScale = 1.0f; // k
    float radius = 0.06f;      // splat radius (world units)
    float strength = 1.0f;     // pigment per second at full alpha
    Emission emission = Emission::Vertices;
    float surfaceStep = 0.02f; // UV-space step of surface emission
    uint32_t maxEmitters = 256;
    float sleepThreshold = 1e-4f; // below this pigment and speed, the solver sleeps
    // Afterimage smear.
    AfterimageSpec afterimage;
    // Swept volume.
    SweptVolumeSpec swept;
    // Silhouette shell.
    SilhouetteShellSpec shell;
};

struct Scene {
    std::string file; // where it came from ("(built-in default)" for the default scene)
    CharacterSpec character;
    CameraSpec camera;
    std::vector<LightSpec> lights{LightSpec{}};
    StageSpec stage;
    OutputSpec output;
    std::vector<EffectSpec> effects;
};

const char* effectTypeName(EffectType type);

// Parses and checks a scene's JSON text; `where` names it in errors (a file name).
Result<Scene> parseScene(const std::string& text, const std::string& where);
// Reads and parses a scene file.
Result<Scene> loadScene(const std::filesystem::path& file);
// The built-in default: the fighter's roundhouse kick with speed-lines, a blur volume on the
// kicking leg and smoke from the kicking foot.
Scene defaultScene();

// What `motionfx render CHARACTER.glb` plays: the file's first clip (or character.clip, once
// set), framed by fitScene, with the default scene's speed-lines, blur volume and smoke bound to
// the fastest limb at automatic strides. `file` is named as given (relative to the working
// directory).
Scene previewScene(const std::string& file);
// Whether a command's first word names a character file (.gltf or .glb) rather than a scene.
bool isCharacterFile(const std::string& path);

// Loads the scene's character (the built-in fighter or a glTF file relative to the scene file's
// folder), scales it to a sane size (scene_fit.h: chooseCharacterScale; `note`, when not null,
// gets the line saying so) and checks the clip and every effect's bone and mesh names against it
// (checkNames).
Result<anim::Character> loadCharacter(const Scene& scene, std::string* note = nullptr);
// Checks that the character has the scene's clip and that playback starts inside it.
Status checkClip(const Scene& scene, const anim::Character& character);
// checkClip, then every effect's bone (plain names, groups and patterns) and mesh names.
Status checkNames(const Scene& scene, const anim::Character& character);

// Seconds of scene time the output covers, and the clip time at a scene time.
float sceneDuration(const Scene& scene, const anim::Character& character);
uint32_t frameCount(const Scene& scene, const anim::Character& character);
float clipTimeAt(const Scene& scene, const anim::Character& character, float sceneTime);
const anim::Clip& sceneClip(const Scene& scene, const anim::Character& character);

} // namespace mfx::scene
