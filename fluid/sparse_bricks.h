// A sparse grid's layout: where smoke may be simulated in a virtual domain far larger than any
// dense grid (the first step of the sparse domain; the solver stages over it come next).
//
// The virtual domain is cut into bricks of kBrickSize^3 cells. A brick table holds, for every
// virtual brick, its slot in an atlas of brick storage, or kNoSlot while the brick is inactive.
// Each step the wanted set is built again from the emitters' footprints and the cells still above
// the sleep threshold, dilated by the advection's reach; commit() then frees the bricks no longer
// wanted (their slots return to a free list) and gives slots to the newly wanted ones, growing the
// atlas by doubling up to a budget of bricks. Past the budget a wanted brick is refused (counted,
// left inactive), never a crash; the bricks already active keep their slots first, since they
// hold smoke.
//
// Why 8^3 cells a brick:
//   * 512 cells are two of the solver's 8x8x4 workgroups, so a dispatch over active bricks keeps
//     whole workgroups busy with no partial groups at a brick's edge;
//   * the ring of bricks the dilation adds around the smoke is one brick thick (a step's
//     back-trace stays within 8 cells below a CFL number of 8): with 8^3 bricks that ring costs far
//     less than with NVIDIA Flow's 32x16x16 blocks around a small puff;
//   * the table stays dense and small: a 256^3 virtual domain is 32^3 = 32,768 entries (128 KiB),
//     read with one index computation, no hashing; 4^3 bricks would make it 8 times larger and
//     give each brick's bookkeeping (its dispatch entry, its neighbour lookups) 8 times fewer
//     cells.
#pragma once

#include "shaders/shared/sparse_fluid.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace mfx::fluid {

inline constexpr uint32_t kBrickSize = MFX_BRICK_SIZE;
inline constexpr uint32_t kNoSlot = MFX_NO_SLOT;
static_assert(MFX_BRICK_CELLS == kBrickSize * kBrickSize * kBrickSize);
static_assert(MFX_BRICK_FACES == (kBrickSize + 1) * kBrickSize * kBrickSize);

class SparseBricks {
public:
    // A virtual domain of `bricks` bricks per axis, with storage for at most `maxBricks`; the
    // atlas starts with `initialSlots` (at most maxBricks) and doubles when it runs out.
    SparseBricks(glm::uvec3 bricks, uint32_t maxBricks, uint32_t initialSlots = 64);

    glm::uvec3 bricks() const { return bricks_; }
    glm::uvec3 cells() const { return bricks_ * kBrickSize; }
    uint32_t maxBricks() const { return maxBricks_; }

    // The atlas slot of brick (x, y, z), or kNoSlot (inactive, or outside the domain).
    uint32_t slot(glm::ivec3 brick) const;
    // The atlas slot holding cell (x, y, z), or kNoSlot.
    uint32_t cellSlot(glm::ivec3 cell) const;

    // Building the wanted set of a step: start empty, then add.
    void clearWanted();
    // An emitter's footprint: every brick a sphere (centre and radius in cells) touches; the part
    // outside the domain is cut off.
    void wantSphere(glm::vec3 centre, float radius);
    // A moving solid's footprint: every brick whose cell centres' bounding sphere (its centre,
    // 3.5 √3 cells wide, and a hundredth of a cell for fp32's error) meets the capsule of axis
    // a-b and `radius`, all in cells (a cell's centre is at its index + 0.5); the part outside
    // the domain is cut off. Non-finite or negative values want nothing.
    void wantCapsule(glm::vec3 a, glm::vec3 b, float radius);
    // A cell above the sleep threshold.
    void wantCell(glm::ivec3 cell);
    // Every brick within `cells` cells of a wanted brick (the advection's reach), inside the
    // domain.
    void dilate(uint32_t cells);
    bool wanted(glm::ivec3 brick) const;

    // The wanted set becomes the active set.
    struct Update {
        std::vector<uint32_t> activated; // brick indices given slots this step, ascending
        std::vector<uint32_t> freed;     // brick indices whose slots were freed, ascending
        uint32_t refused = 0;            // wanted bricks left inactive: the budget was reached
    };
    Update commit();

    uint32_t activeCount() const { return activeCount_; }
    // Slots the atlas has (used or free): what storage holds now.
    uint32_t capacity() const { return capacity_; }
    // The active bricks' indices, ascending (x fastest): the list an indirect dispatch walks.
    std::vector<uint32_t> activeList() const;
    // The slot of every brick (x fastest), kNoSlot where inactive: the GPU's brick table.
    const std::vector<uint32_t>& table() const { return table_; }
    // One flag per cell of the virtual domain (x fastest): 1 in active bricks.
    std::vector<uint8_t> activeCells() const;
    uint32_t index(glm::ivec3 brick) const {
        return uint32_t(brick.x) + bricks_.x * (uint32_t(brick.y) + bricks_.y * uint32_t(brick.z));
    }
    bool inside(glm::ivec3 brick) const;

private:
    glm::uvec3 bricks_;
    uint32_t maxBricks_;
    uint32_t capacity_;
    std::vector<uint32_t> table_; // slot per brick
    std::vector<uint8_t> wanted_; // per brick, this step
    std::vector<uint32_t> free_;  // free slots, the lowest last
    uint32_t activeCount_ = 0;
};

// From a brick table (a slot per brick, x fastest, kNoSlot where inactive; SparseBricks's own or
// one read back from the GPU): the active bricks' indices, ascending, and one flag per cell of the
// virtual domain of `bricks` bricks a side (1 in an active brick).
std::vector<uint32_t> activeBricksOf(const std::vector<uint32_t>& table);
std::vector<uint8_t> activeCellsOf(const std::vector<uint32_t>& table, glm::uvec3 bricks);

} // namespace mfx::fluid
