#include "core/math/dual_quat.h"

#include <cmath>

namespace mfx::math {

DualQuat DualQuat::fromRigid(const glm::quat& rotation, const glm::vec3& translation) {
    const glm::quat t(0.0f, translation.x, translation.y, translation.z);
    return {rotation, 0.5f * (t * rotation)};
}

glm::vec3 DualQuat::translation() const {
    const glm::quat t = 2.0f * (dual * glm::conjugate(real));
    return {t.x, t.y, t.z};
}

glm::vec3 DualQuat::transformPoint(const glm::vec3& p) const {
    return real * p + translation();
}

glm::vec3 DualQuat::transformVector(const glm::vec3& v) const {
    return real * v;
}

DualQuat DualQuat::normalized() const {
    const float length = glm::length(real);
    if (!(length > 0.0f)) return {};
    return {real / length, dual / length};
}

DualQuat operator*(float s, const DualQuat& q) {
    return {s * q.real, s * q.dual};
}

DualQuat operator+(const DualQuat& a, const DualQuat& b) {
    return {a.real + b.real, a.dual + b.dual};
}

DualQuat alignedWith(const DualQuat& q, const DualQuat& reference) {
    return glm::dot(q.real, reference.real) < 0.0f ? -1.0f * q : q;
}

DualQuat blend(const DualQuat& a, const DualQuat& b, float t) {
    return ((1.0f - t) * a + t * alignedWith(b, a)).normalized();
}

Decomposed decompose(const glm::mat4& m) {
    Decomposed d;
    d.translation = glm::vec3(m[3]);
    glm::vec3 x(m[0]), y(m[1]), z(m[2]);
    d.scale = {glm::length(x), glm::length(y), glm::length(z)};
    if (glm::dot(glm::cross(x, y), z) < 0.0f) {
        d.scale.x = -d.scale.x;
        x = -x;
    }
    // Gram-Schmidt: the rotation of the columns with any shear removed.
    const glm::vec3 u = glm::normalize(x);
    const glm::vec3 v = glm::normalize(y - glm::dot(y, u) * u);
    const glm::vec3 w = glm::cross(u, v);
    if (!std::isfinite(u.x + u.y + u.z + v.x + v.y + v.z)) return d; // a degenerate matrix
    d.rotation = glm::normalize(glm::quat_cast(glm::mat3(u, v, w)));
    return d;
}

} // namespace mfx::math
