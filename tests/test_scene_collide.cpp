// A scene's smoke colliding with its character ("collide", on by default; docs/fluid.md "Solids"):
// the fighter's body capsules become each step's solids in the grid's coordinates; off, the grid
// has none and steps as before, bit for bit; "collide_bones" picks capsules by bone entries; bad
// bone entries are refused naming the entry.
#include "core/anim/body_capsules.h"
#include "core/anim/fighter.h"
#include "fluid/reference/reference_solver.h"
#include "sim/scene_simulation.h"
#include "tests/gpu_test.h"
#include "tests/scene_sim_util.h"

#include <algorithm>
#include <cstdio>

namespace mfx::test {
namespace {

using SceneCollideTest = GpuTest;

// The kick with smoke from the right foot, 24³ cells of 8 cm, `extra` keys added to the effect.
scene::Scene kickScene(const std::string& extra, uint32_t frames) {
    return parseScene(R"({"character": {"clip": "roundhouse_kick"}, "output": {"frames": )" +
                      std::to_string(frames) + R"(}, "effects": [{"type": "smoke",
                      "bones": ["foot_r", "toe_r"], "grid": [24, 24, 24], "cell_size": 0.08,
                      "fade": 0.5, "radius": 0.12)" +
                      extra + "}]}");
}

// The share of the grid's pigment (alpha) in the cells its last step's solids cover, and how many
// cells those are.
double pigmentInside(const sim::SceneSimulation::SmokeGrid& grid, uint64_t* solidCells = nullptr) {
    fluid::ReferenceSolver marks(grid.grid.options());
    marks.setSolids(grid.lastSolids);
    const fluid::FieldState state = const_cast<fluid::SmokeGrid&>(grid.grid).state();
    const fluid::GridShape& g = state.grid;
    double inside = 0.0, total = 0.0;
    for (int k = 0; k < int(g.cellsZ); ++k)
        for (int j = 0; j < int(g.cellsY); ++j)
            for (int i = 0; i < int(g.cellsX); ++i) {
                const double alpha = state.pigment[g.index(i, j, k) * 4 + 3];
                total += alpha;
                if (marks.solidCell({i, j, k})) {
                    inside += alpha;
                    if (solidCells) ++*solidCells;
                }
            }
    return total > 0.0 ? inside / total : 0.0;
}

// The kick's frames with and without "collide" (and `extra` keys in both): the largest share of
// the pigment in the body's cells over the frames after the sixth, with and without.
void kickInAndOut(const gpu::Context& ctx, uint32_t frames, const std::string& extra) {
    const anim::Character fighter = anim::makeFighter();
    auto with = simulate(ctx, kickScene(extra, frames), fighter); // on by default
    auto without = simulate(ctx, kickScene(R"(, "collide": false)" + extra, frames), fighter);
    ASSERT_TRUE(with && without);
    ASSERT_TRUE(with->smokeGrids()[0].collides());
    EXPECT_FALSE(without->smokeGrids()[0].collides());
    double largestWith = 0.0, largestWithout = 0.0;
    for (uint32_t f = 0; f < frames; ++f) {
        const sim::SimulationFrameStats stats = with->runFrame(f);
        without->runFrame(f);
        if (f < 6) continue; // the smoke has to be made first
        const auto& grid = with->smokeGrids()[0];
        ASSERT_FALSE(grid.lastSolids.empty()) << "frame " << f;
        uint64_t solidCells = 0;
        largestWith = std::max(largestWith, pigmentInside(grid, &solidCells));
        // The frame's statistics count the same cells (fp32 against the reference's fp64).
        ASSERT_EQ(stats.grids.size(), 1u);
        EXPECT_EQ(stats.grids[0].solids, grid.lastSolids.size());
        EXPECT_GT(solidCells, 0u);
        EXPECT_NEAR(double(stats.grids[0].solidCells), double(solidCells),
                    0.01 * double(solidCells))
            << "frame " << f;
        // Without collision, the same body's cells (as the colliding grid had them this frame).
        sim::SceneSimulation::SmokeGrid& other = without->smokeGrids()[0];
        other.lastSolids = grid.lastSolids;
        largestWithout = std::max(largestWithout, pigmentInside(other));
        other.lastSolids.clear();
    }
    std::printf("the kick's smoke in the body's cells%s: at most %.3g of it with \"collide\", "
                "%.3g without\n",
                extra.c_str(), largestWith, largestWithout);
    EXPECT_LE(largestWith, 0.01);
    EXPECT_GT(largestWithout, largestWith) << "the comparison could not fail";
}

TEST_F(SceneCollideTest, TheKicksSmokeStaysOutOfTheBodyInEveryFrame) {
    kickInAndOut(ctx(), 36, "");
}

// On the sparse domain: the rebuild keeps the body's bricks active, the stages the same rules.
TEST_F(SceneCollideTest, TheKicksSmokeStaysOutOfTheBodyOnTheSparseDomain) {
    kickInAndOut(ctx(), 24, R"(, "domain": "sparse")");
}

// The same with MGPCG, whose level 0 reads the solids and whose coarse levels do not.
TEST_F(SceneCollideTest, TheKicksSmokeStaysOutOfTheBodyWithMgpcg) {
    kickInAndOut(ctx(), 20, R"(, "pressure": "mgpcg")");
}

TEST_F(SceneCollideTest, CollideBonesPickTheCapsulesAndABadEntryIsRefused) {
    const anim::Character fighter = anim::makeFighter();
    auto all = simulate(ctx(), kickScene(R"(, "collide": true)", 2), fighter);
    auto leg = simulate(ctx(),
                        kickScene(R"(, "collide": true, "collide_bones": ["@right_leg"],
                                         "collide_thickness": 0.3)",
                                  2),
                        fighter);
    ASSERT_TRUE(all && leg);
    const size_t allCapsules = all->smokeGrids()[0].capsules[0].size();
    const size_t legCapsules = leg->smokeGrids()[0].capsules[0].size();
    // Without "collide_bones", every capsule but those of the bones the smoke comes from (the
    // foot's, foot_r and toe_r: smoke born inside a solid would be cleared where it is born).
    const std::vector<anim::BodyCapsule> every = anim::fitBodyCapsules(fighter);
    auto emits = [&](const anim::BodyCapsule& c) {
        const std::string& name = fighter.nodes[size_t(c.node)].name;
        return name == "foot_r" || name == "toe_r";
    };
    const size_t emitting = size_t(std::count_if(every.begin(), every.end(), emits));
    EXPECT_GT(emitting, 0u);
    EXPECT_EQ(allCapsules, every.size() - emitting);
    for (const anim::BodyCapsule& c : all->smokeGrids()[0].capsules[0])
        EXPECT_FALSE(emits(c)) << fighter.nodes[size_t(c.node)].name;
    EXPECT_GT(legCapsules, 0u);
    EXPECT_LT(legCapsules, allCapsules);
    leg->runFrame(0);
    leg->runFrame(1);
    for (const shared::FluidSolid& s : leg->smokeGrids()[0].lastSolids)
        EXPECT_GE(s.endA.w, 0.15f) << "the thickness raises every radius to half of it";

    const scene::Scene bad =
        kickScene(R"(, "collide": true, "collide_bones": ["no_such_bone"])", 2);
    auto refused = sim::SceneSimulation::create(ctx(), bad, fighter);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("effects[0].collide_bones[0]"), std::string::npos)
        << refused.error().message;
    EXPECT_EQ(refused.error().message.find('\n'), std::string::npos);
}

} // namespace
} // namespace mfx::test
