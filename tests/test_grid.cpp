// The simulation grid's shape and its checks.
#include "fluid/grid.h"

#include <cmath>
#include <gtest/gtest.h>

namespace mfx::fluid {
namespace {

TEST(GridShape, IndexIsXFastest) {
    const GridShape grid{96, 64, 48, 0.1f};
    EXPECT_EQ(grid.cellCount(), 96u * 64u * 48u);
    EXPECT_EQ(grid.index(0, 0, 0), 0u);
    EXPECT_EQ(grid.index(1, 0, 0), 1u);
    EXPECT_EQ(grid.index(0, 1, 0), 96u);
    EXPECT_EQ(grid.index(0, 0, 1), 96u * 64u);
    EXPECT_EQ(grid.index(95, 63, 47), grid.cellCount() - 1);
}

TEST(GridShape, ValidationNamesTheBadValue) {
    EXPECT_TRUE(validateGrid({96, 64, 48, 0.1f}, 4096).ok());
    EXPECT_TRUE(validateGrid({1, 64, 64, 0.1f}, 4096).ok());
    const Status tooThin = validateGrid({64, 0, 64, 0.1f}, 4096);
    ASSERT_FALSE(tooThin.ok());
    EXPECT_NE(tooThin.error().message.find("y dimension"), std::string::npos);
    const Status tooBig = validateGrid({64, 64, 5000, 0.1f}, 4096);
    ASSERT_FALSE(tooBig.ok());
    EXPECT_NE(tooBig.error().message.find("z dimension"), std::string::npos);
    EXPECT_FALSE(validateGrid({8, 8, 8, 0.0f}, 4096).ok());
    EXPECT_FALSE(validateGrid({8, 8, 8, -1.0f}, 4096).ok());
    EXPECT_FALSE(validateGrid({8, 8, 8, std::nanf("")}, 4096).ok());
    EXPECT_FALSE(validateGrid({8, 8, 8, INFINITY}, 4096).ok());
}

} // namespace
} // namespace mfx::fluid
