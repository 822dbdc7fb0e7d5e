// Unit dual quaternions for rigid transforms (rotation + translation), the blending rule of dual
// quaternion skinning, and the split of an affine matrix into translation, rotation and scale.
// docs/architecture.md "Formulas": skinning blends dual quaternions with the sign rule against the
// first joint and blends scale linearly; trajectory sub-samples blend two dual quaternions with the
// same rule (Kavan et al., "Geometric skinning with approximate dual quaternion blending", 2008).
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace mfx::math {

struct DualQuat {
    glm::quat real{1.0f, 0.0f, 0.0f, 0.0f}; // rotation
    glm::quat dual{0.0f, 0.0f, 0.0f, 0.0f}; // 0.5 * translation * rotation

    // The rigid transform x -> rotation * x + translation.
    static DualQuat fromRigid(const glm::quat& rotation, const glm::vec3& translation);

    glm::vec3 translation() const; // of a unit dual quaternion
    glm::vec3 transformPoint(const glm::vec3& p) const;
    glm::vec3 transformVector(const glm::vec3& v) const;

    // Divides both parts by |real|, making it a unit dual quaternion again after a blend.
    DualQuat normalized() const;
};

DualQuat operator*(float s, const DualQuat& q);
DualQuat operator+(const DualQuat& a, const DualQuat& b);

// `q` or `-q` (the same rigid transform), whichever has a real part facing `reference`
// (non-negative 4D dot product): blending then takes the short way round.
DualQuat alignedWith(const DualQuat& q, const DualQuat& reference);

// (1 - t) a + t b with the sign rule, normalised: a at t = 0, b at t = 1.
DualQuat blend(const DualQuat& a, const DualQuat& b, float t);

// An affine matrix split as M = T * R * S (S per axis). A mirroring matrix (negative
// determinant) gets a negative x scale. Shear, which T R S cannot hold, is dropped: the rotation
// is that of the orthonormalised columns.
struct Decomposed {
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 scale{1.0f};
};
Decomposed decompose(const glm::mat4& m);

} // namespace mfx::math
