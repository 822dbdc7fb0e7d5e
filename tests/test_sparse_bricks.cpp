// A sparse grid's layout (fluid/sparse_bricks.h): the bricks an emitter's footprint wants are
// exactly those its sphere touches, the dilation adds the advection's reach, commit() frees what
// fell inactive and reuses its slots, the atlas doubles up to its budget, and past the budget
// bricks are refused and counted while the active ones keep their slots.
#include "fluid/sparse_bricks.h"

#include <gtest/gtest.h>

#include <set>

namespace mfx::test {
namespace {

using fluid::kBrickSize;
using fluid::kNoSlot;
using fluid::SparseBricks;

// Whether a sphere touches brick (x, y, z), by its cells: some point of the brick's box within
// the radius, found on a fine lattice of the box (the test's own, independent of the layout's).
bool touches(glm::ivec3 brick, glm::vec3 centre, float radius) {
    const float b = float(kBrickSize);
    for (int k = 0; k <= 32; ++k)
        for (int j = 0; j <= 32; ++j)
            for (int i = 0; i <= 32; ++i) {
                const glm::vec3 p = (glm::vec3(brick) + glm::vec3(i, j, k) / 32.0f) * b;
                if (glm::length(p - centre) <= radius) return true;
            }
    return false;
}

TEST(SparseBricks, ASpheresFootprintIsTheBricksItTouches) {
    SparseBricks layout({8, 8, 8}, 512);
    const glm::vec3 centre(21.5f, 30.25f, 9.0f);
    const float radius = 9.5f;
    layout.wantSphere(centre, radius);
    int wanted = 0;
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) {
                EXPECT_EQ(layout.wanted({x, y, z}), touches({x, y, z}, centre, radius))
                    << x << " " << y << " " << z;
                wanted += layout.wanted({x, y, z});
            }
    EXPECT_GT(wanted, 8);
    EXPECT_LT(wanted, 40);
}

TEST(SparseBricks, AFootprintAtTheDomainsEdgeIsCutOffAndOneOutsideIsIgnored) {
    SparseBricks layout({4, 4, 4}, 64);
    layout.wantSphere({-3.0f, 1.0f, 1.0f}, 4.0f); // reaches into brick (0, 0, 0) only
    EXPECT_TRUE(layout.wanted({0, 0, 0}));
    layout.clearWanted();
    layout.wantSphere({-20.0f, 5.0f, 5.0f}, 4.0f);
    layout.wantSphere({100.0f, 5.0f, 5.0f}, 4.0f);
    layout.wantSphere({5.0f, 5.0f, 5.0f}, std::numeric_limits<float>::quiet_NaN());
    layout.wantCell({-1, 3, 3});
    layout.wantCell({32, 3, 3});
    EXPECT_EQ(layout.commit().activated.size(), 0u);
}

TEST(SparseBricks, DilationAddsTheAdvectionsReachInBricks) {
    SparseBricks layout({9, 9, 9}, 729);
    layout.wantCell({4 * 8 + 3, 4 * 8 + 3, 4 * 8 + 3}); // a cell of brick (4, 4, 4)
    layout.dilate(1);                                   // one cell's reach: the bricks around it
    int wanted = 0;
    for (int z = 0; z < 9; ++z)
        for (int y = 0; y < 9; ++y)
            for (int x = 0; x < 9; ++x) {
                const bool near =
                    std::abs(x - 4) <= 1 && std::abs(y - 4) <= 1 && std::abs(z - 4) <= 1;
                EXPECT_EQ(layout.wanted({x, y, z}), near) << x << " " << y << " " << z;
                wanted += layout.wanted({x, y, z});
            }
    EXPECT_EQ(wanted, 27);
    layout.dilate(9); // 9 cells reach two bricks further: 7^3
    int further = 0;
    for (int z = 0; z < 9; ++z)
        for (int y = 0; y < 9; ++y)
            for (int x = 0; x < 9; ++x)
                further += layout.wanted({x, y, z});
    EXPECT_EQ(further, 7 * 7 * 7);
}

TEST(SparseBricks, CommitFreesWhatFellInactiveAndReusesItsSlots) {
    SparseBricks layout({4, 4, 4}, 64, 4);
    layout.wantCell({1, 1, 1});  // brick 0
    layout.wantCell({9, 1, 1});  // brick 1
    layout.wantCell({17, 1, 1}); // brick 2
    SparseBricks::Update u = layout.commit();
    EXPECT_EQ(u.activated, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(layout.slot({0, 0, 0}), 0u);
    EXPECT_EQ(layout.slot({1, 0, 0}), 1u);
    EXPECT_EQ(layout.cellSlot({17, 1, 1}), 2u);
    EXPECT_EQ(layout.cellSlot({-1, 1, 1}), kNoSlot);
    // Brick 1 falls inactive; a new brick takes its slot, the others keep theirs.
    layout.clearWanted();
    layout.wantCell({1, 1, 1});
    layout.wantCell({17, 1, 1});
    layout.wantCell({1, 9, 1}); // brick (0, 1, 0), index 4
    u = layout.commit();
    EXPECT_EQ(u.freed, (std::vector<uint32_t>{1}));
    EXPECT_EQ(u.activated, (std::vector<uint32_t>{4}));
    EXPECT_EQ(layout.slot({1, 0, 0}), kNoSlot);
    EXPECT_EQ(layout.slot({0, 1, 0}), 1u) << "the freed slot serves the new brick";
    EXPECT_EQ(layout.slot({0, 0, 0}), 0u);
    EXPECT_EQ(layout.slot({2, 0, 0}), 2u);
    EXPECT_EQ(layout.activeCount(), 3u);
    EXPECT_EQ(layout.activeList(), (std::vector<uint32_t>{0, 2, 4}));
    EXPECT_EQ(layout.capacity(), 4u) << "no growth needed";
}

TEST(SparseBricks, TheAtlasDoublesUpToItsBudgetAndRefusesPastIt) {
    SparseBricks layout({8, 8, 8}, 40, 4);
    for (int x = 0; x < 8; ++x)
        for (int y = 0; y < 3; ++y)
            layout.wantCell({x * 8, y * 8, 0}); // 24 bricks
    SparseBricks::Update u = layout.commit();
    EXPECT_EQ(u.activated.size(), 24u);
    EXPECT_EQ(u.refused, 0u);
    EXPECT_EQ(layout.capacity(), 32u) << "4, 8, 16, 32";
    // 24 more wanted, 16 left in the budget: the active ones keep their slots.
    for (int x = 0; x < 8; ++x)
        for (int y = 3; y < 6; ++y)
            layout.wantCell({x * 8, y * 8, 0});
    u = layout.commit();
    EXPECT_EQ(u.activated.size(), 16u);
    EXPECT_EQ(u.refused, 8u);
    EXPECT_EQ(layout.capacity(), 40u) << "grown to the budget, not past it";
    EXPECT_EQ(layout.activeCount(), 40u);
    std::set<uint32_t> slots;
    for (uint32_t i : layout.activeList())
        slots.insert(layout.slot({int(i % 8), int(i / 8 % 8), int(i / 64)}));
    EXPECT_EQ(slots.size(), 40u) << "every active brick its own slot";
    EXPECT_EQ(*slots.rbegin(), 39u);
    for (int x = 0; x < 8; ++x)
        EXPECT_NE(layout.slot({x, 0, 0}), kNoSlot) << "the first bricks kept theirs";
}

TEST(SparseBricks, ABrickActivatedAndDeactivatedEveryStepKeepsTheAtlasSteady) {
    SparseBricks layout({4, 4, 4}, 8, 2);
    for (int step = 0; step < 2000; ++step) {
        layout.clearWanted();
        layout.wantCell({1, 1, 1});
        if (step % 2 == 0) layout.wantCell({25, 25, 25});
        const SparseBricks::Update u = layout.commit();
        ASSERT_EQ(u.refused, 0u);
        ASSERT_EQ(layout.activeCount(), step % 2 == 0 ? 2u : 1u);
    }
    EXPECT_EQ(layout.capacity(), 2u);
}

} // namespace
} // namespace mfx::test
