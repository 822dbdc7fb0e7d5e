// Fitting a scene to whatever character it loads, so that a rig of any unit, size and naming
// convention gives a framed picture with visible effects and no per-rig tuning:
//
//   * size: a character whose height (its skinned vertices at the first frame of the scene's
//     clip) lies outside [kSaneHeightLow, kSaneHeightHigh] metres is scaled uniformly to
//     kDefaultHeight (anim::scaleCharacter); character.height or character.scale override it.
//     Every length default of the scene (cell size, splat radius, ribbon width, camera, stage) is
//     in metres for a human-sized character and so fits every character after this;
//   * bones: an effect's "bones" may name bone groups and glob patterns (core/anim/bone_groups.h),
//     resolved here to the rig's bone names; an effect with neither bones nor meshes binds to the
//     limb that moves fastest over its window;
//   * strides: an effect without "stride" takes the stride that leaves about kTargetLines lines
//     (speed-lines) or kTargetParticles points (particles) of the vertices it selects, whatever
//     the mesh's vertex count (smoke samples its vertices by max_emitters instead);
//   * framing: a scene without "camera" is framed on the characters' animated bounds over the
//     played range (at most 240 frames and about 2,048 vertices a primitive are sampled), from a
//     three-quarter view of the way they face (of one character: its facing; of several: their
//     facings' sum, or, where they cancel, as fighters facing each other do, the side of the line
//     between the first two), with the floor at the lowest point the characters reach and the
//     shadow box, backdrop and near/far planes sized to those bounds.
#pragma once

#include "core/anim/character.h"
#include "core/anim/sampling.h"
#include "core/result.h"
#include "core/scene/scene.h"

#include <span>
#include <string>
#include <vector>

namespace mfx::scene {

constexpr float kDefaultHeight = 1.8f;  // what an outlier is scaled to, metres
constexpr float kSaneHeightLow = 1.0f;  // heights in [low, high] are left alone
constexpr float kSaneHeightHigh = 2.5f; //
constexpr uint32_t kTargetLines = 150;
constexpr uint32_t kTargetParticles = 300;

struct Bounds {
    glm::vec3 low{0.0f};
    glm::vec3 high{0.0f};
    bool empty() const { return low.x > high.x; }
    glm::vec3 centre() const { return 0.5f * (low + high); }
    glm::vec3 size() const { return high - low; }
};

// A character placed in the world (its position, then yaw about +y).
glm::mat4 characterPlacement(const CharacterSpec& character);
// Character `c`'s pose (not placed) at scene time `time`: its clip at clipTimeAt. Every pose the
// set-up, the simulation and the renderers sample goes through it.
anim::Pose characterPose(const Scene& scene, size_t c, const anim::Character& character,
                         float time);

// The bounds of the character's skinned vertices in `pose` (in its own frame, not placed); at
// most about `maxVertices` vertices a primitive are visited (an even stride through each).
Bounds poseBounds(const anim::Character& character, const anim::Pose& pose,
                  size_t maxVertices = 4096);
// The height of character `c`'s skinned vertices at the first frame played (0 without vertices).
float characterHeight(const Scene& scene, size_t c, const anim::Character& character);
// Whether scene time `time` is inside effect `e`'s window, with half a frame of slack at each end
// (so a boundary on a frame time is inside it): the rule every effect is played by.
bool effectLive(const Scene& scene, const EffectSpec& e, float time);

// The frames (of `frames`) at which effect `e` is live: all of them, or at most kMaxSampledFrames
// spread evenly over them. What the set-up samples an effect's motion at (its fastest limb,
// whether it moves, where its smoke goes), so that its cost does not grow with the scene's length.
constexpr size_t kMaxSampledFrames = 240;
std::vector<uint32_t> liveSampledFrames(const Scene& scene, const EffectSpec& e, uint32_t frames);

// The bounds of the placed characters over the scene's played range (at most kMaxSampledFrames
// frames of it, spread evenly).
Bounds animatedBounds(const Scene& scene, std::span<const anim::Character> cast);
inline Bounds animatedBounds(const Scene& scene, const anim::Character& character) {
    return animatedBounds(scene, std::span<const anim::Character>(&character, 1));
}

// The uniform scale loadCharacter applies to character `c`: 1 inside the sane range; `note` (when
// not null) gets the line that tells the user what was done (empty when nothing was). `where`
// names the file.
float chooseCharacterScale(const Scene& scene, size_t c, const anim::Character& character,
                           const std::string& where, std::string* note);

// Resolves every effect's bone groups and patterns into bone names, binds effects that name no
// bone or mesh to the fastest limb, chooses strides, frames the camera and sizes the stage
// (whichever of these the scene leaves to it), and checks every name; each effect on the
// character it follows. Idempotent: what it set is no longer automatic. `notes` (when not null)
// gets one line per choice made for the user. The cast has one character per scene.characters
// entry.
Status fitScene(Scene& scene, std::span<const anim::Character> cast,
                std::vector<std::string>* notes = nullptr);
inline Status fitScene(Scene& scene, const anim::Character& character,
                       std::vector<std::string>* notes = nullptr) {
    return fitScene(scene, std::span<const anim::Character>(&character, 1), notes);
}

// Effects whose selected vertices never move while they are live over `frames` frames (or that
// are never live): what they draw is empty. One entry per effect: its name and why.
std::vector<std::string> motionlessEffects(const Scene& scene,
                                           std::span<const anim::Character> cast, uint32_t frames);
inline std::vector<std::string>
motionlessEffects(const Scene& scene, const anim::Character& character, uint32_t frames) {
    return motionlessEffects(scene, std::span<const anim::Character>(&character, 1), frames);
}

} // namespace mfx::scene
