#include "core/scene/scene_fit.h"

#include "core/scene/scene_hits.h"

#include "core/anim/bone_groups.h"
#include "core/anim/sampling.h"
#include "core/anim/skinning.h"
#include "core/trajectory/build_segment.h"
#include "core/trajectory/trajectory_source.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <set>

namespace mfx::scene {

std::vector<uint32_t> liveSampledFrames(const Scene& scene, const EffectSpec& e, uint32_t frames) {
    std::vector<uint32_t> live;
    const float dt = 1.0f / scene.output.fps;
    for (uint32_t f = 0; f < frames; ++f)
        if (effectLive(scene, e, float(f) * dt)) live.push_back(f);
    if (live.size() <= kMaxSampledFrames) return live;
    std::vector<uint32_t> out;
    for (size_t k = 0; k < kMaxSampledFrames; ++k)
        out.push_back(live[k * (live.size() - 1) / (kMaxSampledFrames - 1)]);
    return out;
}

namespace {

// The default camera's three-quarter view of a character facing +z: from in front and to the
// viewer's right (+x, the character's left), slightly above (the direction from the target to
// the camera).
const glm::vec3 kThreeQuarterView = glm::normalize(glm::vec3(2.6f, 0.55f, 3.4f));
constexpr float kFrameFill = 0.95f;    // the framed bounds fill at most this much of the frame
constexpr float kEffectMargin = 0.08f; // the effects' reach beyond the body, in heights

std::string formatNumber(double v, int digits = 3) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    return text;
}

std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names)
        out += (out.empty() ? "" : ", ") + n;
    return out;
}

Bounds emptyBounds() {
    return {glm::vec3(std::numeric_limits<float>::max()),
            glm::vec3(std::numeric_limits<float>::lowest())};
}

void include(Bounds& b, glm::vec3 p) {
    b.low = glm::min(b.low, p);
    b.high = glm::max(b.high, p);
}

// The frames at which the scene is sampled for its bounds and motion (every frame, or an even
// subset of a long render).
std::vector<uint32_t> sampledFrames(uint32_t frames) {
    std::vector<uint32_t> out;
    const uint32_t step =
        std::max<uint32_t>(1, uint32_t((frames + kMaxSampledFrames - 1) / kMaxSampledFrames));
    for (uint32_t f = 0; f < frames; f += step)
        out.push_back(f);
    if (out.back() != frames - 1) out.push_back(frames - 1);
    return out;
}

trajectory::Selection selectionOf(const EffectSpec& e) {
    trajectory::Selection s;
    s.meshes = e.meshes;
    s.bones = e.bones;
    s.minBoneWeight = e.minBoneWeight;
    return s;
}

// The peak speed of any bone of `bones` (their world origins, metres per second) over the frames
// where `e` is live: at each of `liveFrames` (liveSampledFrames), from the frame before it (when
// that is live too and the clip does not wrap between them). `c` is the character `e` follows.
float peakBoneSpeed(const Scene& scene, size_t c, const anim::Character& character,
                    const EffectSpec& e, const std::vector<uint32_t>& liveFrames,
                    const std::vector<std::string>& bones) {
    std::vector<int> nodes;
    for (const std::string& b : bones)
        if (std::optional<int> n = character.findNode(b)) nodes.push_back(*n);
    const CharacterSpec& spec = scene.characters[c];
    const glm::mat4 placement = characterPlacement(spec);
    const float dt = 1.0f / scene.output.fps;
    auto positionsAt = [&](uint32_t f) {
        const anim::Pose pose = characterPose(scene, c, character, float(f) * dt);
        std::vector<glm::vec3> out;
        for (int n : nodes)
            out.push_back(glm::vec3(placement * pose.world[size_t(n)][3]));
        return out;
    };
    float peak = 0.0f;
    std::optional<uint32_t> heldFrame; // the last frame whose positions are `held`
    std::vector<glm::vec3> held;
    for (uint32_t f : liveFrames) {
        if (f == 0 || !effectLive(scene, e, float(f - 1) * dt)) continue;
        if (clipTimeAt(spec, character, float(f) * dt) <
            clipTimeAt(spec, character, float(f - 1) * dt))
            continue; // a loop's wrap: the pose jumps back there
        const std::vector<glm::vec3> previous =
            heldFrame == f - 1 ? std::move(held) : positionsAt(f - 1);
        held = positionsAt(f);
        heldFrame = f;
        for (size_t i = 0; i < held.size(); ++i)
            peak = std::max(peak, glm::length(held[i] - previous[i]) / dt);
    }
    return peak;
}

// Binds an effect that names no bone or mesh to the limb that moves fastest over its window.
std::string bindFastestLimb(const Scene& scene, std::span<const anim::Character> cast,
                            EffectSpec& e) {
    const size_t c = effectCharacter(scene, e);
    const anim::Character& character = cast[c];
    std::string best;
    std::vector<std::string> bestBones;
    float bestSpeed = -1.0f;
    const std::vector<uint32_t> liveFrames = liveSampledFrames(scene, e, frameCount(scene, cast));
    for (const std::string& limb : anim::limbGroupNames()) {
        std::vector<std::string> bones = anim::resolveBoneGroup(character, limb);
        if (bones.empty()) continue;
        // The limb must hold vertices (a recognised name on a bone that skins nothing is no use).
        trajectory::Selection selection = selectionOf(e);
        selection.bones = bones;
        if (!trajectory::selectSource(character, selection)) continue;
        const float speed = peakBoneSpeed(scene, c, character, e, liveFrames, bones);
        if (speed > bestSpeed) {
            best = limb;
            bestBones = std::move(bones);
            bestSpeed = speed;
        }
    }
    if (best.empty())
        return "bound to the whole character (no bones given, and no limb recognised among its "
               "bones)";
    e.bones = bestBones;
    return "bound to " + best + ", the fastest limb over its window (no bones given; peak " +
           formatNumber(bestSpeed) + " m/s): " + join(bestBones);
}

// The number of vertices an effect's trail is built from is its selection over the stride; the
// automatic stride leaves about `target` of them.
uint32_t targetCount(const EffectSpec& e) {
    switch (e.kind().strideTarget()) {
    case StrideTarget::Lines:
        return kTargetLines;
    case StrideTarget::Particles:
        return kTargetParticles;
    case StrideTarget::EveryVertex:
        break;
    }
    return 0; // every vertex: blur volumes, smoke (sampled by max_emitters), mesh effects
}

// A character the scene sized outside the human range on purpose (character.height or .scale)
// gets the length defaults of the effects that follow it scaled with it, so a 10 m giant's smoke
// grid and ribbons are as big on it as the defaults are on a human; lengths the file gives are
// kept.
void scaleLengthDefaults(Scene& scene, size_t c, const anim::Character& character,
                         std::vector<std::string>* notes) {
    if (scene.effects.empty()) return;
    const float height = characterHeight(scene, c, character);
    if (!(height > 0.0f) || (height >= kSaneHeightLow && height <= kSaneHeightHigh)) return;
    const float unit = height / kDefaultHeight;
    std::vector<std::string> scaled;
    for (EffectSpec& e : scene.effects) {
        if (effectCharacter(scene, e) != c) continue;
        for (const auto& [key, value] : e.kind().lengths()) {
            if (e.given(key)) continue;
            *value *= unit;
            e.givenKeys.push_back(key); // once: fitting again keeps it
            if (std::find(scaled.begin(), scaled.end(), key) == scaled.end()) scaled.push_back(key);
        }
    }
    if (notes && !scaled.empty())
        notes->push_back("the character" +
                         (scene.characters.size() > 1 ? " \"" + scene.characters[c].name + "\""
                                                      : std::string()) +
                         " is " + formatNumber(height) + " m tall: the effects' default " +
                         join(scaled) + " scaled by " + formatNumber(unit) + " to match");
}

// The way the framing looks at the cast from (see scene_fit.h): one character's facing, the sum
// of several's, or where they cancel, the side of the line between the first two.
glm::vec3 castFacing(const Scene& scene) {
    auto facingOf = [](const CharacterSpec& c) {
        const float yaw = glm::radians(c.yawDegrees);
        return glm::vec3(std::sin(yaw), 0.0f, std::cos(yaw));
    };
    glm::vec3 sum(0.0f);
    for (const CharacterSpec& c : scene.characters)
        sum += facingOf(c);
    if (scene.characters.size() == 1 || glm::length(sum) > 0.3f * float(scene.characters.size()))
        return glm::length(sum) > 1e-6f ? glm::normalize(sum) : glm::vec3(0, 0, 1);
    glm::vec3 across = scene.characters[1].position - scene.characters[0].position;
    across.y = 0.0f;
    if (glm::length(across) < 1e-6f) return facingOf(scene.characters.front());
    return glm::normalize(glm::cross(glm::normalize(across), glm::vec3(0, 1, 0)));
}

void frameCamera(Scene& scene, std::span<const anim::Character> cast) {
    const Bounds body = animatedBounds(scene, cast);
    if (body.empty()) return;
    const float height = std::max(body.size().y, 1e-3f);
    // Lengths scale with the character: its largest extent (a long, low creature gets a stage
    // as long as it is).
    const float unit = std::max({height, body.size().x, body.size().z}) / kDefaultHeight;
    Bounds framed = body;
    framed.low -= glm::vec3(kEffectMargin * height);
    framed.high += glm::vec3(kEffectMargin * height);

    const glm::vec3 facingDirection = castFacing(scene);
    const float yaw = std::atan2(facingDirection.x, facingDirection.z);
    const glm::mat3 turn = glm::mat3(glm::rotate(glm::mat4(1.0f), yaw, glm::vec3(0, 1, 0)));
    const glm::vec3 toCamera = turn * kThreeQuarterView;
    const glm::vec3 forward = -toCamera;
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, forward);
    const glm::vec3 target = framed.centre();
    const float tanV = std::tan(glm::radians(scene.camera.fovDegrees) * 0.5f) * kFrameFill;
    const float tanH =
        tanV * float(scene.output.width) / float(std::max<uint32_t>(scene.output.height, 1));
    // Each corner q of the box must lie inside the view cone: |q.up| <= (D - q.toCamera) tanV,
    // and the same across; the least distance D that holds for all eight.
    float distance = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? framed.high.x : framed.low.x,
                          (corner & 2) ? framed.high.y : framed.low.y,
                          (corner & 4) ? framed.high.z : framed.low.z);
        const glm::vec3 q = p - target;
        const float along = glm::dot(q, toCamera);
        distance = std::max(distance, along + std::abs(glm::dot(q, up)) / tanV);
        distance = std::max(distance, along + std::abs(glm::dot(q, right)) / tanH);
    }
    const float radius = 0.5f * glm::length(framed.size());
    scene.camera.position = target + toCamera * distance;
    scene.camera.target = target;
    scene.camera.nearPlane = std::clamp(0.5f * (distance - radius), 1e-3f * unit, 0.05f * unit);
    scene.camera.farPlane = distance + 60.0f * unit; // past the backdrop and the floor's far edge
    scene.camera.automatic = false;

    // The stage: the floor where the lowest point of the character goes, the backdrop behind it
    // (across the character's facing), the shadow box around everything it reaches.
    StageSpec& stage = scene.stage;
    const glm::vec3 centre = body.centre();
    stage.floorHeight = body.low.y;
    stage.floorCentre = glm::vec3(centre.x, 0.0f, centre.z);
    stage.floorHalfSize = 40.0f * unit;
    const glm::vec3 facing = turn * glm::vec3(0, 0, 1);
    float behind = 0.0f; // how far the body reaches behind its centre, along -facing
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? body.high.x : body.low.x,
                          (corner & 2) ? body.high.y : body.low.y,
                          (corner & 4) ? body.high.z : body.low.z);
        behind = std::max(behind, -glm::dot(p - centre, facing));
    }
    stage.backdropHalfHeight = 10.0f * unit;
    stage.backdropCentre = glm::vec3(centre.x, stage.floorHeight, centre.z) -
                           facing * (behind + 3.5f * unit) +
                           glm::vec3(0.0f, stage.backdropHalfHeight, 0.0f);
    stage.backdropHalfWidth = glm::cross(glm::vec3(0, 1, 0), facing) * (40.0f * unit);
    stage.shadowCentre = centre;
    stage.shadowRadius = std::max(2.5f * unit, 0.5f * glm::length(body.size()) + 0.5f * unit);
}

} // namespace

anim::Pose characterPose(const Scene& scene, size_t c, const anim::Character& character,
                         float time) {
    const CharacterSpec& spec = scene.characters[c];
    return anim::samplePose(character, &sceneClip(spec, character),
                            clipTimeAt(spec, character, performanceTime(scene, time)),
                            anim::Wrap::Clamp);
}

float characterHeight(const Scene& scene, size_t c, const anim::Character& character) {
    if (character.clips.empty()) return 0.0f;
    const Bounds b = poseBounds(character, characterPose(scene, c, character, 0.0f));
    return b.empty() ? 0.0f : b.size().y;
}

bool effectLive(const Scene& scene, const EffectSpec& e, float time) {
    const float slack = 0.5f / scene.output.fps;
    return time + slack >= e.start && (!e.end || time <= *e.end + slack);
}

glm::mat4 characterPlacement(const CharacterSpec& character) {
    return glm::translate(glm::mat4(1.0f), character.position) *
           glm::rotate(glm::mat4(1.0f), glm::radians(character.yawDegrees),
                       glm::vec3(0.0f, 1.0f, 0.0f));
}

Bounds poseBounds(const anim::Character& character, const anim::Pose& pose, size_t maxVertices) {
    Bounds b = emptyBounds();
    for (const anim::Mesh& mesh : character.meshes)
        for (const anim::Primitive& p : mesh.primitives) {
            const size_t count = p.positions.size();
            if (count == 0) continue;
            const size_t stride = std::max<size_t>(1, (count + maxVertices - 1) / maxVertices);
            if (p.skin < 0) {
                const glm::mat4 m = p.node < 0 ? glm::mat4(1.0f) : pose.world[size_t(p.node)];
                for (size_t v = 0; v < count; v += stride)
                    include(b, glm::vec3(m * glm::vec4(p.positions[v], 1.0f)));
                continue;
            }
            const std::vector<anim::DualQuatJoint> palette =
                anim::dualQuatPalette(anim::jointMatrices(character, p.skin, pose));
            for (size_t v = 0; v < count; v += stride)
                include(b, anim::skinDualQuat(palette, p.positions[v], glm::vec3(0, 1, 0),
                                              p.joints[v], p.weights[v])
                               .position);
        }
    return b;
}

Bounds animatedBounds(const Scene& scene, std::span<const anim::Character> cast) {
    Bounds out = emptyBounds();
    const std::vector<uint32_t> frames = sampledFrames(frameCount(scene, cast));
    for (size_t c = 0; c < cast.size() && c < scene.characters.size(); ++c) {
        const glm::mat4 placement = characterPlacement(scene.characters[c]);
        for (uint32_t f : frames) {
            const Bounds b = poseBounds(
                cast[c], characterPose(scene, c, cast[c], float(f) / scene.output.fps), 2048);
            if (b.empty()) continue;
            for (int corner = 0; corner < 8; ++corner)
                include(out,
                        glm::vec3(placement * glm::vec4((corner & 1) ? b.high.x : b.low.x,
                                                        (corner & 2) ? b.high.y : b.low.y,
                                                        (corner & 4) ? b.high.z : b.low.z, 1.0f)));
        }
    }
    return out;
}

float chooseCharacterScale(const Scene& scene, size_t c, const anim::Character& character,
                           const std::string& where, std::string* note) {
    if (note) note->clear();
    if (character.clips.empty()) return 1.0f;
    const float height = characterHeight(scene, c, character);
    const CharacterSpec& spec = scene.characters[c];
    const std::string path = scene.characters.size() == 1 ? std::string("character")
                                                          : "characters[" + std::to_string(c) + "]";
    float factor = 1.0f;
    std::string why;
    if (spec.scale) {
        factor = *spec.scale;
        why = " (" + path + ".scale)";
    } else if (spec.height) {
        if (!(height > 0.0f)) return 1.0f; // nothing to measure: nothing to scale by
        factor = *spec.height / height;
        why = " (" + path + ".height)";
    } else if (height > 0.0f && (height < kSaneHeightLow || height > kSaneHeightHigh)) {
        factor = kDefaultHeight / height;
        why = "; set " + path + ".height or " + path + ".scale to change";
    }
    // A factor a float cannot hold (a scale of 1e-50, a height measured as infinite) scales
    // nothing rather than collapsing the character.
    if (!std::isfinite(factor) || !(factor > 0.0f) || factor == 1.0f) return 1.0f;
    if (note) {
        char metres[32];
        std::snprintf(metres, sizeof metres, "%.2f", double(height * factor));
        *note = where + " is " + formatNumber(height) + " units tall: scaled by " +
                formatNumber(factor) + " to " + metres + " m" + why;
    }
    return factor;
}

Status fitScene(Scene& scene, std::span<const anim::Character> cast,
                std::vector<std::string>* notes) {
    if (Status names = checkNames(scene, cast); !names) return names;
    for (size_t i = 0; i < scene.effects.size(); ++i) {
        EffectSpec& e = scene.effects[i];
        const anim::Character& character = cast[effectCharacter(scene, e)];
        const std::string path = "effects[" + std::to_string(i) + "] \"" + e.name + "\"";
        if (e.automaticBones) {
            const std::string choice = bindFastestLimb(scene, cast, e);
            e.automaticBones = false;
            if (notes) notes->push_back(path + ": " + choice);
        } else if (!e.bones.empty()) {
            std::vector<std::string> bones;
            std::set<std::string> seen;
            for (const std::string& entry : e.bones) {
                // checkNames above resolved every entry; a failure here cannot happen.
                const Result<std::vector<std::string>> resolved =
                    anim::resolveBoneEntry(character, entry);
                if (!resolved)
                    return Error{scene.file + ": " + path + ": " + resolved.error().message};
                for (const std::string& b : resolved.value())
                    if (seen.insert(b).second) bones.push_back(b);
            }
            e.bones = std::move(bones);
        }
        if (e.automaticStride) {
            e.automaticStride = false;
            const uint32_t target = targetCount(e);
            uint32_t* stride = e.kind().strideValue();
            if (target == 0 || !stride) continue;
            const Result<trajectory::Source> source =
                trajectory::selectSource(character, selectionOf(e));
            if (!source) // the simulation reports it, with the effect's path
                continue;
            const size_t count = source.value().vertices.size();
            *stride = std::max<uint32_t>(1, uint32_t(std::lround(double(count) / target)));
        }
    }
    for (size_t c = 0; c < cast.size(); ++c)
        scaleLengthDefaults(scene, c, cast[c], notes);
    // The impacts' hits (on the performance without hit-stops), once.
    if (!scene.hitsFound) {
        scene.hits.clear();
        Result<std::vector<Hit>> hits = findHits(scene, cast);
        if (!hits) return hits.error();
        scene.hits = std::move(hits).value();
        scene.hitsFound = true;
    }
    if (scene.camera.automatic) frameCamera(scene, cast);
    return Ok{};
}

std::vector<std::string> motionlessEffects(const Scene& scene,
                                           std::span<const anim::Character> cast, uint32_t frames) {
    std::vector<std::string> out;
    const float dt = 1.0f / scene.output.fps;
    const float renderEnd = float(frames) * dt;
    for (const EffectSpec& e : scene.effects) {
        const size_t c = effectCharacter(scene, e);
        if (c >= cast.size()) continue;
        const anim::Character& character = cast[c];
        const glm::mat4 placement = characterPlacement(scene.characters[c]);
        // Smoke paints its pigment where its vertices are even at rest, and the smear variant of
        // the afterimage draws the mesh itself: both show something without motion.
        if (e.kind().showsAtRest()) continue;
        const Result<trajectory::Source> selected =
            trajectory::selectSource(character, selectionOf(e));
        if (!selected) continue; // refused elsewhere, with a reason
        // An even sample of at most 1024 of its vertices.
        trajectory::Source source = selected.value();
        const size_t stride = std::max<size_t>(1, (source.vertices.size() + 1023) / 1024);
        std::vector<shared::SkinVertexIn> sample;
        for (size_t v = 0; v < source.vertices.size(); v += stride)
            sample.push_back(source.vertices[v]);
        source.vertices = std::move(sample);
        auto positions = [&](float t) {
            const auto transforms = trajectory::vertexTransforms(
                source, trajectory::sourcePalette(
                            character, source, characterPose(scene, c, character, t), placement));
            std::vector<glm::vec3> p(transforms.size());
            for (size_t v = 0; v < p.size(); ++v)
                p[v] = anim::applyTransform(transforms[v], glm::vec3(source.vertices[v].position),
                                            glm::vec3(0, 1, 0))
                           .position;
            return p;
        };
        // Each live frame's segment runs from the previous frame's pose to this one; a sample of
        // them, as for the fastest limb.
        const std::vector<uint32_t> live = liveSampledFrames(scene, e, frames);
        const bool everLive = !live.empty();
        float largest = 0.0f;
        Bounds reach = emptyBounds();
        std::optional<uint32_t> heldFrame; // the last frame whose positions are `held`
        std::vector<glm::vec3> held;
        for (uint32_t f : live) {
            const float t = float(f) * dt;
            const std::vector<glm::vec3> previous = heldFrame && *heldFrame + 1 == f
                                                        ? std::move(held)
                                                        : positions(std::max(t - dt, 0.0f));
            held = positions(t);
            heldFrame = f;
            for (size_t v = 0; v < held.size(); ++v) {
                largest = std::max(largest, glm::length(held[v] - previous[v]));
                include(reach, held[v]);
            }
        }
        const std::string window = formatNumber(e.start) + "-" +
                                   (e.end ? formatNumber(*e.end) : std::string("end")) + " s";
        if (!everLive) {
            out.push_back("\"" + e.name + "\" (its window " + window +
                          " is outside the render, 0-" + formatNumber(renderEnd) + " s)");
            continue;
        }
        // Still, to a millionth of the size of what it covers (or of a micrometre).
        const float size = std::max(glm::length(reach.size()), 1.0f);
        if (largest <= 1e-6f * size)
            out.push_back("\"" + e.name + "\" (its vertices never move in its window " + window +
                          ")");
    }
    return out;
}

} // namespace mfx::scene
