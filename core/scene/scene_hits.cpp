#include "core/scene/scene_hits.h"

#include "core/anim/body_capsules.h"
#include "core/anim/capsule_contact.h"
#include "core/scene/kinds/impact_effect.h"
#include "core/scene/scene_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace mfx::scene {

namespace {

// Of a character's body capsules `all`, those on `bones` (every one when `bones` is empty).
std::vector<anim::BodyCapsule> capsulesOf(const anim::Character& character,
                                          std::vector<anim::BodyCapsule> all,
                                          const std::vector<std::string>& bones) {
    if (bones.empty()) return all;
    std::erase_if(all, [&](const anim::BodyCapsule& c) {
        return std::find(bones.begin(), bones.end(), character.nodes[size_t(c.node)].name) ==
               bones.end();
    });
    return all;
}

// The capsules posed and placed in the world.
std::vector<anim::PosedCapsule> posed(const std::vector<anim::BodyCapsule>& capsules,
                                      const anim::Pose& pose, const glm::mat4& placement) {
    std::vector<anim::PosedCapsule> out;
    out.reserve(capsules.size());
    for (const anim::BodyCapsule& c : capsules) {
        anim::PosedCapsule p = anim::poseCapsule(c, pose);
        p.a = glm::vec3(placement * glm::vec4(p.a, 1.0f));
        p.b = glm::vec3(placement * glm::vec4(p.b, 1.0f));
        out.push_back(p);
    }
    return out;
}

float gapBetween(const anim::PosedCapsule& x, const anim::PosedCapsule& y) {
    const anim::SegmentPoints p = anim::closestPoints(x.a, x.b, y.a, y.b);
    return glm::distance(p.p, p.q) - x.radius - y.radius;
}

// Whether two capsules swept over a frame can come within touching: their bounding spheres over
// the frame, a cheap test that skips most pairs of a body far from the other.
bool mayMeet(const anim::SweptCapsule& x, const anim::SweptCapsule& y) {
    auto sphere = [](const anim::SweptCapsule& c, glm::vec3& centre) {
        centre = 0.25f * (c.from.a + c.from.b + c.to.a + c.to.b);
        float r = 0.0f;
        for (glm::vec3 p : {c.from.a, c.from.b, c.to.a, c.to.b})
            r = std::max(r, glm::distance(p, centre));
        return r + std::max(c.from.radius, c.to.radius);
    };
    glm::vec3 cx, cy;
    const float rx = sphere(x, cx), ry = sphere(y, cy);
    return glm::distance(cx, cy) <= rx + ry;
}

// One impact's blow against one target, as the frames go by.
struct Strike {
    size_t effect = 0, attacker = 0, target = 0;
    std::vector<anim::BodyCapsule> attackerCapsules, targetCapsules;
    std::vector<anim::PosedCapsule> attackerBefore, targetBefore; // at the frame's start
};

struct FrameHit {
    Hit hit;
    float fraction = 0.0f; // of the performance frame
};

} // namespace

Result<std::vector<Hit>> findHits(const Scene& scene, std::span<const anim::Character> cast) {
    std::vector<Hit> hits;
    if (cast.size() != scene.characters.size()) return hits;
    std::vector<Strike> strikes;
    // Each character's body capsules, fitted once (on the first strike that needs them).
    std::vector<std::optional<std::vector<anim::BodyCapsule>>> bodies(cast.size());
    auto body = [&](size_t c) -> const std::vector<anim::BodyCapsule>& {
        if (!bodies[c]) bodies[c] = anim::fitBodyCapsules(cast[c]);
        return *bodies[c];
    };
    for (size_t i = 0; i < scene.effects.size(); ++i) {
        const EffectSpec& e = scene.effects[i];
        const ImpactSpec* impact = e.as<ImpactSpec>();
        if (!impact) continue;
        const size_t attacker = effectCharacter(scene, e);
        for (size_t t = 0; t < cast.size(); ++t) {
            if (t == attacker) continue;
            if (!impact->target.empty() && scene.characters[t].name != impact->target) continue;
            Strike s;
            s.effect = i;
            s.attacker = attacker;
            s.target = t;
            s.attackerCapsules = capsulesOf(cast[attacker], body(attacker), e.bones);
            s.targetCapsules = body(t);
            if (!s.attackerCapsules.empty() && !s.targetCapsules.empty())
                strikes.push_back(std::move(s));
        }
    }
    if (strikes.empty()) return hits;

    // The performance, frame by frame (scene.hits is empty: characterPose gives it unheld).
    const float fps = scene.output.fps;
    const uint32_t frames = frameCount(scene, cast);
    uint64_t tests = 0;
    for (const Strike& s : strikes)
        tests += uint64_t(s.attackerCapsules.size()) * s.targetCapsules.size() * frames;
    if (tests > kMaxHitTests)
        return Error{scene.file + ": the impacts would test " + std::to_string(tests) +
                     " pairs of body capsules over " + std::to_string(frames) +
                     " frames; at most " + std::to_string(kMaxHitTests) +
                     " (fewer impacts, a target for each, fewer bones or frames)"};
    std::vector<anim::Pose> before(cast.size()), now(cast.size());
    std::vector<glm::mat4> placements;
    for (size_t c = 0; c < cast.size(); ++c) {
        placements.push_back(characterPlacement(scene.characters[c]));
        before[c] = characterPose(scene, c, cast[c], 0.0f);
    }
    for (Strike& s : strikes) {
        s.attackerBefore = posed(s.attackerCapsules, before[s.attacker], placements[s.attacker]);
        s.targetBefore = posed(s.targetCapsules, before[s.target], placements[s.target]);
    }
    uint32_t held = 0; // hit-stop frames so far
    for (uint32_t g = 1; g < frames && hits.size() < kMaxHits; ++g) {
        for (size_t c = 0; c < cast.size(); ++c)
            now[c] = characterPose(scene, c, cast[c], float(g) / fps);
        std::vector<FrameHit> found;
        for (Strike& s : strikes) {
            const std::vector<anim::PosedCapsule> attackerNow =
                posed(s.attackerCapsules, now[s.attacker], placements[s.attacker]);
            const std::vector<anim::PosedCapsule> targetNow =
                posed(s.targetCapsules, now[s.target], placements[s.target]);
            // Touching when the frame starts: the blow that touched is still going on (armed
            // again once apart).
            bool touching = false;
            for (const anim::PosedCapsule& a : s.attackerBefore)
                for (const anim::PosedCapsule& b : s.targetBefore)
                    touching = touching || gapBetween(a, b) <= 0.0f;
            std::optional<FrameHit> earliest;
            if (!touching) {
                for (size_t a = 0; a < attackerNow.size(); ++a)
                    for (size_t b = 0; b < targetNow.size(); ++b) {
                        const anim::SweptCapsule x{s.attackerBefore[a], attackerNow[a]};
                        const anim::SweptCapsule y{s.targetBefore[b], targetNow[b]};
                        if (!mayMeet(x, y)) continue;
                        const std::optional<anim::CapsuleContact> contact =
                            anim::firstContact(x, y, 1.0f / fps);
                        if (!contact || (earliest && earliest->fraction <= contact->time)) continue;
                        FrameHit h;
                        h.fraction = contact->time;
                        h.hit.effect = s.effect;
                        h.hit.attacker = s.attacker;
                        h.hit.target = s.target;
                        h.hit.point = contact->point;
                        h.hit.direction = contact->direction;
                        h.hit.speed = contact->speed;
                        h.hit.attackerBone =
                            cast[s.attacker].nodes[size_t(s.attackerCapsules[a].node)].name;
                        h.hit.targetBone =
                            cast[s.target].nodes[size_t(s.targetCapsules[b].node)].name;
                        earliest = h;
                    }
            }
            if (earliest) found.push_back(*earliest);
            s.attackerBefore = attackerNow;
            s.targetBefore = targetNow;
        }
        std::stable_sort(found.begin(), found.end(), [](const FrameHit& x, const FrameHit& y) {
            return x.fraction < y.fraction;
        });
        for (FrameHit& f : found) {
            Hit& h = f.hit;
            h.time = (float(g - 1) + f.fraction + float(held)) / fps;
            h.frame = g + held;
            // An impact lands only inside its window (in scene time).
            if (!effectLive(scene, scene.effects[h.effect], h.time)) continue;
            h.holdFrames = scene.effects[h.effect].as<ImpactSpec>()->hitStopFrames;
            held += h.holdFrames;
            if (hits.size() < kMaxHits) hits.push_back(h);
        }
        before.swap(now);
    }
    return hits;
}

const ImpactSpec* hitImpact(const Scene& scene, const Hit& hit) {
    return hit.effect < scene.effects.size() ? scene.effects[hit.effect].as<ImpactSpec>() : nullptr;
}

glm::vec3 cameraShake(const Scene& scene, float time) {
    glm::vec3 offset(0.0f);
    for (size_t k = 0; k < scene.hits.size(); ++k) {
        const Hit& h = scene.hits[k];
        const ImpactSpec* impact = hitImpact(scene, h);
        if (!impact || impact->shake <= 0.0f) continue;
        const float age = time - h.time;
        if (age < 0.0f || age >= impact->shakeSeconds) continue;
        const float fade = 1.0f - age / impact->shakeSeconds;
        const float amplitude = impact->shake * fade * fade;
        const float phase = float(k) * 1.7f;
        const glm::vec3 jitter(std::sin(2.0f * 3.14159265f * 23.0f * age + phase),
                               std::sin(2.0f * 3.14159265f * 29.0f * age + 2.0f * phase + 1.1f),
                               std::sin(2.0f * 3.14159265f * 19.0f * age + 3.0f * phase + 2.3f));
        const glm::vec3 along =
            glm::length(h.direction) > 1e-6f ? glm::normalize(h.direction) : glm::vec3(0.0f);
        offset +=
            amplitude * (0.6f * jitter + 0.4f * along * std::cos(2.0f * 3.14159265f * 11.0f * age));
    }
    return offset;
}

} // namespace mfx::scene
