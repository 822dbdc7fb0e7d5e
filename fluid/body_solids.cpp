#include "fluid/body_solids.h"

#include <algorithm>
#include <limits>

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

namespace {

// The cells of `grid` whose centres a capsule's bounding box holds (low > high on an axis: none).
void capsuleBox(const GridShape& grid, const shared::FluidSolid& s, glm::ivec3& low,
                glm::ivec3& high) {
    const glm::ivec3 n(grid.cellsX, grid.cellsY, grid.cellsZ);
    const float h = grid.cellSize;
    const glm::vec3 a(s.endA), b(s.endB);
    const float r = s.endA.w;
    low = glm::max(glm::ivec3(glm::floor((glm::min(a, b) - r) / h - 0.5f)), glm::ivec3(0));
    high = glm::min(glm::ivec3(glm::ceil((glm::max(a, b) + r) / h - 0.5f)), n - 1);
}

// Calls mark(cell) for every cell of `grid` whose centre lies inside one of `solids`.
template <typename Mark>
void forEachSolidCell(const GridShape& grid, std::span<const shared::FluidSolid> solids,
                      Mark mark) {
    const float h = grid.cellSize;
    for (const shared::FluidSolid& s : solids) {
        const glm::vec3 a(s.endA), b(s.endB);
        const float r = s.endA.w;
        glm::ivec3 low, high;
        capsuleBox(grid, s, low, high);
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
                    if (glm::dot(d, d) < r * r) mark(glm::ivec3(i, j, k));
                }
    }
}

} // namespace

std::vector<uint8_t> solidCellMask(const GridShape& grid,
                                   std::span<const shared::FluidSolid> solids) {
    std::vector<uint8_t> solid(grid.cellCount(), 0);
    forEachSolidCell(grid, solids, [&](glm::ivec3 q) {
        solid[grid.index(uint32_t(q.x), uint32_t(q.y), uint32_t(q.z))] = 1;
    });
    return solid;
}

uint64_t countSolidCells(const GridShape& grid, std::span<const shared::FluidSolid> solids) {
    // A mask over the solids' joint box alone (a sparse domain is far larger than the body).
    glm::ivec3 low(std::numeric_limits<int>::max()), high(std::numeric_limits<int>::min());
    for (const shared::FluidSolid& s : solids) {
        glm::ivec3 lo, hi;
        capsuleBox(grid, s, lo, hi);
        if (glm::any(glm::greaterThan(lo, hi))) continue;
        low = glm::min(low, lo);
        high = glm::max(high, hi);
    }
    if (glm::any(glm::greaterThan(low, high))) return 0;
    const glm::ivec3 size = high - low + 1;
    std::vector<uint8_t> solid(size_t(size.x) * size_t(size.y) * size_t(size.z), 0);
    uint64_t count = 0;
    forEachSolidCell(grid, solids, [&](glm::ivec3 q) {
        const glm::ivec3 l = q - low;
        uint8_t& cell =
            solid[size_t(l.x) + size_t(size.x) * (size_t(l.y) + size_t(size.y) * size_t(l.z))];
        count += cell == 0 ? 1 : 0;
        cell = 1;
    });
    return count;
}

} // namespace mfx::fluid
