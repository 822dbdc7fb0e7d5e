#include "core/anim/capsule_contact.h"

#include <algorithm>
#include <cmath>

namespace mfx::anim {

SegmentPoints closestPoints(glm::vec3 a0, glm::vec3 a1, glm::vec3 b0, glm::vec3 b1) {
    const glm::vec3 d1 = a1 - a0, d2 = b1 - b0, r = a0 - b0;
    const float a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
    const float tiny = 1e-12f;
    float s = 0.0f, t = 0.0f;
    if (a <= tiny && e <= tiny) {
        // Both points.
    } else if (a <= tiny) {
        t = std::clamp(f / e, 0.0f, 1.0f);
    } else {
        const float c = glm::dot(d1, r);
        if (e <= tiny) {
            s = std::clamp(-c / a, 0.0f, 1.0f);
        } else {
            const float b = glm::dot(d1, d2), denominator = a * e - b * b;
            // Parallel segments (denominator 0): any s; take 0.
            s = denominator > tiny * a * e ? std::clamp((b * f - c * e) / denominator, 0.0f, 1.0f)
                                           : 0.0f;
            t = (b * s + f) / e;
            if (t < 0.0f) {
                t = 0.0f;
                s = std::clamp(-c / a, 0.0f, 1.0f);
            } else if (t > 1.0f) {
                t = 1.0f;
                s = std::clamp((b - c) / a, 0.0f, 1.0f);
            }
        }
    }
    return {s, t, a0 + s * d1, b0 + t * d2};
}

namespace {

PosedCapsule at(const SweptCapsule& c, float time) {
    return {glm::mix(c.from.a, c.to.a, time), glm::mix(c.from.b, c.to.b, time),
            c.from.radius + (c.to.radius - c.from.radius) * time};
}

// The gap between two capsules (negative: they overlap) and their closest axis points.
float gap(const PosedCapsule& x, const PosedCapsule& y, SegmentPoints* points = nullptr) {
    const SegmentPoints p = closestPoints(x.a, x.b, y.a, y.b);
    if (points) *points = p;
    return glm::distance(p.p, p.q) - x.radius - y.radius;
}

float travel(const SweptCapsule& c) {
    return std::max(glm::distance(c.from.a, c.to.a), glm::distance(c.from.b, c.to.b));
}

} // namespace

std::optional<CapsuleContact> firstContact(const SweptCapsule& attacker, const SweptCapsule& target,
                                           float seconds) {
    if (gap(attacker.from, target.from) <= 0.0f) return std::nullopt; // touching already
    // Sub-steps: neither capsule moves more than half the two radii between samples.
    const float radii = std::max(attacker.from.radius + target.from.radius, 1e-6f);
    const float moved = travel(attacker) + travel(target);
    const int steps = std::clamp(int(std::ceil(2.0f * moved / radii)), 4, 1024);
    float before = 0.0f;
    for (int i = 1; i <= steps; ++i) {
        const float now = float(i) / float(steps);
        if (gap(at(attacker, now), at(target, now)) > 0.0f) {
            before = now;
            continue;
        }
        // The contact lies in (before, now]: bisect to a millionth of the frame.
        float low = before, high = now;
        for (int k = 0; k < 40 && high - low > 1e-6f; ++k) {
            const float mid = 0.5f * (low + high);
            (gap(at(attacker, mid), at(target, mid)) > 0.0f ? low : high) = mid;
        }
        CapsuleContact contact;
        contact.time = high;
        const PosedCapsule x = at(attacker, high), y = at(target, high);
        SegmentPoints p;
        gap(x, y, &p);
        const glm::vec3 between = p.q - p.p;
        const float length = glm::length(between);
        contact.point = length > 1e-9f ? p.p + between / length * x.radius : p.p;
        // Each contact point's velocity: its segment's ends' motion blended at its parameter.
        const glm::vec3 va =
            glm::mix(attacker.to.a - attacker.from.a, attacker.to.b - attacker.from.b, p.s);
        const glm::vec3 vb =
            glm::mix(target.to.a - target.from.a, target.to.b - target.from.b, p.t);
        const glm::vec3 relative = (va - vb) / std::max(seconds, 1e-9f);
        contact.speed = glm::length(relative);
        contact.direction = contact.speed > 0.0f ? relative / contact.speed : glm::vec3(0.0f);
        return contact;
    }
    return std::nullopt;
}

} // namespace mfx::anim
