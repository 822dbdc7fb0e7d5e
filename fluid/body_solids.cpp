#include "fluid/body_solids.h"

#include <algorithm>

namespace mfx::fluid {

std::vector<shared::FluidSolid> bodySolids(std::span<const anim::BodyCapsule> capsules,
                                           const anim::Pose& before, const anim::Pose& now,
                                           float dt, glm::vec3 origin, float thickness,
                                           const glm::mat4& placement) {
    std::vector<shared::FluidSolid> solids;
    solids.reserve(capsules.size());
    const float scale = glm::length(glm::vec3(placement[0]));
    auto place = [&](glm::vec3 p) { return glm::vec3(placement * glm::vec4(p, 1.0f)); };
    for (const anim::BodyCapsule& capsule : capsules) {
        const anim::PosedCapsule end = anim::poseCapsule(capsule, now);
        const anim::PosedCapsule start = anim::poseCapsule(capsule, before);
        const glm::vec3 a = place(end.a), b = place(end.b);
        const float radius = std::max(end.radius * scale, 0.5f * thickness);
        solids.push_back({glm::vec4(a - origin, radius), glm::vec4(b - origin, 0.0f),
                          glm::vec4((a - place(start.a)) / dt, 0.0f),
                          glm::vec4((b - place(start.b)) / dt, 0.0f)});
    }
    return solids;
}

std::vector<uint8_t> solidCellMask(const GridShape& grid,
                                   std::span<const shared::FluidSolid> solids) {
    const glm::ivec3 n(grid.cellsX, grid.cellsY, grid.cellsZ);
    const float h = grid.cellSize;
    std::vector<uint8_t> solid(grid.cellCount(), 0);
    for (const shared::FluidSolid& s : solids) {
        const glm::vec3 a(s.endA), b(s.endB);
        const float r = s.endA.w;
        // The cells whose centres the capsule's bounding box holds.
        const glm::ivec3 low =
            glm::max(glm::ivec3(glm::floor((glm::min(a, b) - r) / h - 0.5f)), glm::ivec3(0));
        const glm::ivec3 high =
            glm::min(glm::ivec3(glm::ceil((glm::max(a, b) + r) / h - 0.5f)), n - 1);
        const glm::vec3 ab = b - a;
        const float length2 = glm::dot(ab, ab);
        for (int k = low.z; k <= high.z; ++k)
            for (int j = low.y; j <= high.y; ++j)
                for (int i = low.x; i <= high.x; ++i) {
                    const glm::vec3 x = (glm::vec3(i, j, k) + 0.5f) * h;
                    const float t = length2 > 0.0f
                                        ? std::clamp(glm::dot(x - a, ab) / length2, 0.0f, 1.0f)
                                        : 0.0f;
                    const glm::vec3 d = x - (a + t * ab);
                    if (glm::dot(d, d) < r * r)
                        solid[grid.index(uint32_t(i), uint32_t(j), uint32_t(k))] = 1;
                }
    }
    return solid;
}

uint64_t countSolidCells(const GridShape& grid, std::span<const shared::FluidSolid> solids) {
    if (solids.empty()) return 0;
    uint64_t count = 0;
    for (uint8_t cell : solidCellMask(grid, solids))
        count += cell;
    return count;
}

} // namespace mfx::fluid
