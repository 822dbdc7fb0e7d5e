#include "fluid/body_solids.h"

#include <algorithm>

namespace mfx::fluid {

std::vector<shared::FluidSolid> bodySolids(std::span<const anim::BodyCapsule> capsules,
                                           const anim::Pose& before, const anim::Pose& now,
                                           float dt, glm::vec3 origin, float thickness) {
    std::vector<shared::FluidSolid> solids;
    solids.reserve(capsules.size());
    for (const anim::BodyCapsule& capsule : capsules) {
        const anim::PosedCapsule end = anim::poseCapsule(capsule, now);
        const anim::PosedCapsule start = anim::poseCapsule(capsule, before);
        const float radius = std::max(end.radius, 0.5f * thickness);
        solids.push_back({glm::vec4(end.a - origin, radius), glm::vec4(end.b - origin, 0.0f),
                          glm::vec4((end.a - start.a) / dt, 0.0f),
                          glm::vec4((end.b - start.b) / dt, 0.0f)});
    }
    return solids;
}

} // namespace mfx::fluid
