#include "fluid/sparse_bricks.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mfx::fluid {

SparseBricks::SparseBricks(glm::uvec3 bricks, uint32_t maxBricks, uint32_t initialSlots)
    : bricks_(bricks), maxBricks_(maxBricks),
      capacity_(std::min(std::max(initialSlots, 1u), std::max(maxBricks, 1u))) {
    if (bricks.x == 0 || bricks.y == 0 || bricks.z == 0 || maxBricks == 0)
        throw std::invalid_argument("a sparse domain needs at least one brick and a budget of one");
    const size_t count = size_t(bricks.x) * bricks.y * bricks.z;
    table_.assign(count, kNoSlot);
    wanted_.assign(count, 0);
    for (uint32_t s = capacity_; s-- > 0;)
        free_.push_back(s);
}

bool SparseBricks::inside(glm::ivec3 b) const {
    return b.x >= 0 && b.y >= 0 && b.z >= 0 && uint32_t(b.x) < bricks_.x &&
           uint32_t(b.y) < bricks_.y && uint32_t(b.z) < bricks_.z;
}

uint32_t SparseBricks::slot(glm::ivec3 brick) const {
    return inside(brick) ? table_[index(brick)] : kNoSlot;
}

uint32_t SparseBricks::cellSlot(glm::ivec3 cell) const {
    // Floor division: cell -1 is in brick -1 (outside), not brick 0.
    const glm::ivec3 brick(cell.x < 0 ? -1 : cell.x / int(kBrickSize),
                           cell.y < 0 ? -1 : cell.y / int(kBrickSize),
                           cell.z < 0 ? -1 : cell.z / int(kBrickSize));
    return slot(brick);
}

void SparseBricks::clearWanted() {
    std::fill(wanted_.begin(), wanted_.end(), uint8_t(0));
}

void SparseBricks::wantCell(glm::ivec3 cell) {
    if (cell.x < 0 || cell.y < 0 || cell.z < 0) return;
    const glm::ivec3 brick = cell / int(kBrickSize);
    if (inside(brick)) wanted_[index(brick)] = 1;
}

void SparseBricks::wantSphere(glm::vec3 centre, float radius) {
    if (!std::isfinite(centre.x) || !std::isfinite(centre.y) || !std::isfinite(centre.z) ||
        !std::isfinite(radius) || radius < 0.0f)
        return;
    const float b = float(kBrickSize);
    // The bricks of the sphere's bounding box, clipped to the domain, each kept when the sphere
    // reaches its box (the nearest point of the box within the radius).
    const glm::vec3 domain = glm::vec3(bricks_) - 1.0f;
    const glm::vec3 lowF = glm::clamp(glm::floor((centre - radius) / b), glm::vec3(0.0f), domain);
    const glm::vec3 highF = glm::clamp(glm::floor((centre + radius) / b), glm::vec3(0.0f), domain);
    if (centre.x + radius < 0.0f || centre.y + radius < 0.0f || centre.z + radius < 0.0f) return;
    const glm::vec3 extent = glm::vec3(bricks_) * b;
    if (centre.x - radius >= extent.x || centre.y - radius >= extent.y ||
        centre.z - radius >= extent.z)
        return;
    const glm::ivec3 low(lowF), high(highF);
    for (int z = low.z; z <= high.z; ++z)
        for (int y = low.y; y <= high.y; ++y)
            for (int x = low.x; x <= high.x; ++x) {
                const glm::vec3 boxLow = glm::vec3(x, y, z) * b, boxHigh = boxLow + b;
                const glm::vec3 nearest = glm::clamp(centre, boxLow, boxHigh);
                const glm::vec3 d = nearest - centre;
                if (glm::dot(d, d) <= radius * radius) wanted_[index({x, y, z})] = 1;
            }
}

void SparseBricks::wantCapsule(glm::vec3 a, glm::vec3 b, float radius) {
    for (int axis = 0; axis < 3; ++axis)
        if (!std::isfinite(a[axis]) || !std::isfinite(b[axis])) return;
    if (!std::isfinite(radius) || radius < 0.0f) return;
    const float size = float(kBrickSize);
    const float reach = radius + 3.5f * std::sqrt(3.0f) + 0.01f;
    const glm::vec3 low = glm::min(a, b) - reach, high = glm::max(a, b) + reach;
    const glm::vec3 extent = glm::vec3(bricks_) * size;
    for (int axis = 0; axis < 3; ++axis)
        if (high[axis] < 0.0f || low[axis] >= extent[axis]) return;
    const glm::vec3 top = glm::vec3(bricks_) - 1.0f;
    const glm::ivec3 first(glm::clamp(glm::floor(low / size), glm::vec3(0.0f), top));
    const glm::ivec3 last(glm::clamp(glm::floor(high / size), glm::vec3(0.0f), top));
    const glm::vec3 ab = b - a;
    const float length2 = glm::dot(ab, ab);
    for (int z = first.z; z <= last.z; ++z)
        for (int y = first.y; y <= last.y; ++y)
            for (int x = first.x; x <= last.x; ++x) {
                const glm::vec3 centre = glm::vec3(x, y, z) * size + 0.5f * size;
                const float t = length2 > 0.0f
                                    ? std::clamp(glm::dot(centre - a, ab) / length2, 0.0f, 1.0f)
                                    : 0.0f;
                const glm::vec3 d = centre - (a + t * ab);
                if (glm::dot(d, d) <= reach * reach) wanted_[index({x, y, z})] = 1;
            }
}

void SparseBricks::dilate(uint32_t cells) {
    const int reach = int((cells + kBrickSize - 1) / kBrickSize);
    if (reach == 0) return;
    // Separable: along x, then y, then z, each a running window of the marks.
    for (int axis = 0; axis < 3; ++axis) {
        std::vector<uint8_t> next(wanted_.size(), 0);
        for (uint32_t z = 0; z < bricks_.z; ++z)
            for (uint32_t y = 0; y < bricks_.y; ++y)
                for (uint32_t x = 0; x < bricks_.x; ++x) {
                    const glm::ivec3 at(x, y, z);
                    if (!wanted_[index(at)]) continue;
                    for (int d = -reach; d <= reach; ++d) {
                        glm::ivec3 n = at;
                        n[axis] += d;
                        if (inside(n)) next[index(n)] = 1;
                    }
                }
        wanted_.swap(next);
    }
}

bool SparseBricks::wanted(glm::ivec3 brick) const {
    return inside(brick) && wanted_[index(brick)] != 0;
}

SparseBricks::Update SparseBricks::commit() {
    Update update;
    // Free first, so that the slots of bricks that fell inactive serve the new ones.
    for (uint32_t i = 0; i < table_.size(); ++i)
        if (table_[i] != kNoSlot && !wanted_[i]) {
            free_.push_back(table_[i]);
            table_[i] = kNoSlot;
            --activeCount_;
            update.freed.push_back(i);
        }
    // The lowest free slot first: the atlas's used part stays packed at its start.
    std::sort(free_.begin(), free_.end(), std::greater<uint32_t>());
    for (uint32_t i = 0; i < table_.size(); ++i) {
        if (!wanted_[i] || table_[i] != kNoSlot) continue;
        if (free_.empty() && capacity_ < maxBricks_) { // grow: double, up to the budget
            const uint32_t grown = std::min(maxBricks_, std::max(capacity_ * 2, capacity_ + 1));
            for (uint32_t s = grown; s-- > capacity_;)
                free_.push_back(s);
            capacity_ = grown;
        }
        if (free_.empty()) {
            ++update.refused;
            continue;
        }
        table_[i] = free_.back();
        free_.pop_back();
        ++activeCount_;
        update.activated.push_back(i);
    }
    return update;
}

std::vector<uint32_t> SparseBricks::activeList() const {
    return activeBricksOf(table_);
}

std::vector<uint8_t> SparseBricks::activeCells() const {
    return activeCellsOf(table_, bricks_);
}

std::vector<uint32_t> activeBricksOf(const std::vector<uint32_t>& table) {
    std::vector<uint32_t> out;
    for (uint32_t i = 0; i < table.size(); ++i)
        if (table[i] != kNoSlot) out.push_back(i);
    return out;
}

std::vector<uint8_t> activeCellsOf(const std::vector<uint32_t>& table, glm::uvec3 bricks) {
    const glm::uvec3 n = bricks * kBrickSize;
    std::vector<uint8_t> flags(size_t(n.x) * n.y * n.z, 0);
    for (uint32_t z = 0; z < n.z; ++z)
        for (uint32_t y = 0; y < n.y; ++y)
            for (uint32_t x = 0; x < n.x; ++x) {
                const glm::uvec3 b = glm::uvec3(x, y, z) / kBrickSize;
                if (table[b.x + bricks.x * (b.y + size_t(bricks.y) * b.z)] != kNoSlot)
                    flags[x + size_t(n.x) * (y + size_t(n.y) * z)] = 1;
            }
    return flags;
}

} // namespace mfx::fluid
