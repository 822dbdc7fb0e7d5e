// Inputs shared by the trajectory tests: a ring of source vertices bound to one joint, and the
// rigid pose of that joint.
#pragma once

#include "core/anim/skinning.h"
#include "core/trajectory/trajectory_source.h"

#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace mfx::test {

// A source of `count` vertices on a circle of radius `radius` in the xz plane around the origin,
// each bound to palette entry 0 alone.
inline trajectory::Source ringSource(int count, float radius) {
    trajectory::Source s;
    s.palette.push_back({-1, -1, -1});
    for (int i = 0; i < count; ++i) {
        const float a = 6.2831853f * float(i) / float(count);
        shared::SkinVertexIn v{};
        v.position = glm::vec4(radius * std::cos(a), 0.1f * float(i), radius * std::sin(a), 1.0f);
        v.normal = glm::vec4(std::cos(a), 0.0f, std::sin(a), 0.0f);
        v.joints = glm::uvec4(0);
        v.weights = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
        s.vertices.push_back(v);
        s.colours.push_back(glm::vec4(1.0f, 0.5f, 0.2f, 1.0f));
    }
    for (int i = 0; i + 2 < count; ++i)
        s.triangles.insert(s.triangles.end(), {0u, uint32_t(i + 1), uint32_t(i + 2)});
    return s;
}

inline anim::DualQuatJoint rigid(const glm::quat& rotation, const glm::vec3& translation) {
    return {math::DualQuat::fromRigid(rotation, translation), glm::vec3(1.0f)};
}

} // namespace mfx::test
