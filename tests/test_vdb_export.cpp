// OpenVDB export (fluid/vdb_export.h), read back by OpenVDB's own reader: grid names, voxel size,
// transform (y up and z up), active voxel counts and values at sampled cells match the fields
// written; a scene's smoke written frame by frame (render/simulate --vdb) matches its grid's
// state; bad input is one clear error.
#include "apps/commands.h"
#include "core/anim/fighter.h"
#include "core/scene/scene.h"
#include "fluid/body_solids.h"
#include "fluid/vdb_export.h"
#include "tests/cli_run.h"
#include "tests/fluid_test_util.h"
#include "tests/gpu_test.h"
#include "tests/scene_sim_util.h"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <filesystem>
#include <set>

namespace mfx::test {
namespace {

openvdb::GridPtrVecPtr readAll(const std::string& path) {
    openvdb::initialize();
    openvdb::io::File file(path);
    file.open();
    openvdb::GridPtrVecPtr grids = file.getGrids();
    file.close();
    return grids;
}

template <typename GridType>
typename GridType::Ptr named(const openvdb::GridPtrVecPtr& grids, const std::string& name) {
    for (const openvdb::GridBase::Ptr& g : *grids)
        if (g->getName() == name) return openvdb::gridPtrCast<GridType>(g);
    return nullptr;
}

std::string outputPath(const std::string& file) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/vdb";
    std::filesystem::create_directories(dir);
    return dir + "/" + file;
}

// The cell-centred velocity of cell q: the mean of its two faces per axis.
glm::vec3 cellVelocity(const FieldState& s, glm::uvec3 q) {
    glm::vec3 u;
    for (int c = 0; c < 3; ++c) {
        const glm::uvec3 n = fluid::faceExtent(s.grid, c);
        glm::uvec3 hi = q;
        hi[c] += 1;
        u[c] = 0.5f * (component(s, c)[q.x + n.x * (q.y + size_t(n.y) * q.z)] +
                       component(s, c)[hi.x + n.x * (hi.y + size_t(n.y) * hi.z)]);
    }
    return u;
}

// Checks a file against the fields it was written from: names, voxel size, every cell's place in
// the world (`toWorld` of its centre in the grid's y-up frame), the active voxels (pigment where
// alpha > 0 among `stored` cells) and the values of every 5th cell.
void expectFileHolds(const std::string& path, const FieldState& s, glm::vec3 origin,
                     const std::function<glm::vec3(glm::vec3)>& toWorld,
                     const std::function<bool(glm::uvec3)>& stored) {
    const openvdb::GridPtrVecPtr grids = readAll(path);
    std::set<std::string> names;
    for (const auto& g : *grids)
        names.insert(g->getName());
    EXPECT_EQ(names, (std::set<std::string>{"density", "colour", "velocity"}));
    auto density = named<openvdb::FloatGrid>(grids, "density");
    auto colour = named<openvdb::Vec3fGrid>(grids, "colour");
    auto velocity = named<openvdb::Vec3fGrid>(grids, "velocity");
    ASSERT_TRUE(density && colour && velocity);
    EXPECT_EQ(density->getGridClass(), openvdb::GRID_FOG_VOLUME);
    const double h = double(s.grid.cellSize);
    EXPECT_NEAR(density->voxelSize()[0], h, 1e-7);
    EXPECT_NEAR(density->voxelSize()[1], h, 1e-7);
    EXPECT_NEAR(density->voxelSize()[2], h, 1e-7);

    const GridShape& g = s.grid;
    openvdb::Index64 withPigment = 0;
    uint32_t sampled = 0;
    for (uint32_t k = 0; k < g.cellsZ; ++k)
        for (uint32_t j = 0; j < g.cellsY; ++j)
            for (uint32_t i = 0; i < g.cellsX; ++i) {
                const size_t cell = g.index(i, j, k);
                const float alpha = s.pigment[4 * cell + 3];
                const bool on = alpha > 0.0f && stored({i, j, k});
                withPigment += on ? 1 : 0;
                if (cell % 5 != 0) continue;
                ++sampled;
                const openvdb::Coord at{int(i), int(j), int(k)};
                const openvdb::Vec3d world = density->indexToWorld(at);
                const glm::vec3 expected =
                    toWorld(origin + (glm::vec3(i, j, k) + 0.5f) * g.cellSize);
                EXPECT_NEAR(world[0], expected.x, 1e-5) << i << " " << j << " " << k;
                EXPECT_NEAR(world[1], expected.y, 1e-5);
                EXPECT_NEAR(world[2], expected.z, 1e-5);
                EXPECT_EQ(density->tree().isValueOn(at), on);
                if (!on) continue;
                EXPECT_EQ(density->tree().getValue(at), alpha);
                const openvdb::Vec3f c = colour->tree().getValue(at);
                for (int channel = 0; channel < 3; ++channel)
                    EXPECT_NEAR(c[channel],
                                std::max(s.pigment[4 * cell + size_t(channel)], 0.0f) /
                                    std::max(alpha, 1e-4f),
                                1e-5f * std::max(1.0f, c[channel]));
                const glm::vec3 u = toWorld(cellVelocity(s, {i, j, k})) - toWorld(glm::vec3(0.0f));
                const openvdb::Vec3f v = velocity->tree().getValue(at);
                EXPECT_NEAR(v[0], u.x, 1e-6);
                EXPECT_NEAR(v[1], u.y, 1e-6);
                EXPECT_NEAR(v[2], u.z, 1e-6);
            }
    EXPECT_GT(sampled, 50u);
    EXPECT_GT(withPigment, 0u);
    EXPECT_EQ(density->activeVoxelCount(), withPigment);
    EXPECT_EQ(colour->activeVoxelCount(), withPigment);
    EXPECT_EQ(velocity->activeVoxelCount(), withPigment);
}

// Random fields with pigment in about half the cells.
FieldState halfPigmented(const GridShape& g) {
    FieldState s = randomState(g, 8);
    for (size_t cell = 0; cell < g.cellCount(); ++cell)
        if ((cell * 2654435761u >> 7) % 2 == 0)
            for (size_t channel = 0; channel < 4; ++channel)
                s.pigment[4 * cell + channel] = 0.0f;
    return s;
}

TEST(VdbExport, OpenVdbReadsBackTheFieldsWhereTheCellsAre) {
    const GridShape g{12, 10, 8, 0.05f};
    const FieldState s = halfPigmented(g);
    const glm::vec3 origin(1.5f, 0.25f, -2.0f);
    fluid::VdbFrame frame;
    frame.state = &s;
    frame.origin = origin;
    const std::string path = outputPath("y_up.vdb");
    ASSERT_TRUE(fluid::writeVdb(path, frame).ok());
    expectFileHolds(
        path, s, origin, [](glm::vec3 p) { return p; }, [](glm::uvec3) { return true; });
}

TEST(VdbExport, ZUpTurnsTheAxesAsBlendersGltfImportDoes) {
    const GridShape g{8, 12, 10, 0.1f};
    const FieldState s = halfPigmented(g);
    const glm::vec3 origin(-0.4f, 0.0f, 0.3f);
    fluid::VdbFrame frame;
    frame.state = &s;
    frame.origin = origin;
    frame.up = fluid::VdbUp::Z;
    const std::string path = outputPath("z_up.vdb");
    ASSERT_TRUE(fluid::writeVdb(path, frame).ok());
    expectFileHolds(
        path, s, origin, [](glm::vec3 p) { return glm::vec3(p.x, -p.z, p.y); },
        [](glm::uvec3) { return true; });
}

TEST(VdbExport, ASparseDomainWritesOnlyItsStoredCells) {
    const GridShape g{16, 8, 8, 0.05f};
    const FieldState s = halfPigmented(g);
    std::vector<uint8_t> stored(g.cellCount(), 0);
    for (uint32_t k = 0; k < g.cellsZ; ++k)
        for (uint32_t j = 0; j < g.cellsY; ++j)
            for (uint32_t i = 0; i < 8; ++i) // the first brick
                stored[g.index(i, j, k)] = 1;
    fluid::VdbFrame frame;
    frame.state = &s;
    frame.storedCells = &stored;
    const std::string path = outputPath("sparse.vdb");
    ASSERT_TRUE(fluid::writeVdb(path, frame).ok());
    expectFileHolds(
        path, s, glm::vec3(0.0f), [](glm::vec3 p) { return p; },
        [](glm::uvec3 q) { return q.x < 8; });
}

// A frame with solids (a scene's "collide") gains a "solid" fog volume: 1 in the solid cells, a
// sphere's here, and none elsewhere; without solids the file has no such grid.
TEST(VdbExport, SolidsBecomeASolidGrid) {
    const GridShape g{16, 8, 8, 0.05f};
    const FieldState s = halfPigmented(g);
    const shared::FluidSolid ball{glm::vec4(0.4f, 0.2f, 0.2f, 0.12f),
                                  glm::vec4(0.4f, 0.2f, 0.2f, 0), glm::vec4(0.0f), glm::vec4(0.0f)};
    const std::vector<uint8_t> solid = fluid::solidCellMask(g, std::span(&ball, 1));
    const uint64_t cells = fluid::countSolidCells(g, std::span(&ball, 1));
    EXPECT_GT(cells, 20u); // about 4/3 pi (0.12 / 0.05)^3 = 58 cells
    EXPECT_LT(cells, 100u);
    fluid::VdbFrame frame;
    frame.state = &s;
    frame.solidCells = &solid;
    const std::string path = outputPath("solid.vdb");
    ASSERT_TRUE(fluid::writeVdb(path, frame).ok());
    const auto grids = readAll(path);
    const openvdb::FloatGrid::Ptr read = named<openvdb::FloatGrid>(grids, "solid");
    ASSERT_TRUE(read);
    EXPECT_EQ(read->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_EQ(read->activeVoxelCount(), cells);
    const auto access = read->getConstAccessor();
    for (uint32_t k = 0; k < g.cellsZ; ++k)
        for (uint32_t j = 0; j < g.cellsY; ++j)
            for (uint32_t i = 0; i < g.cellsX; ++i) {
                const glm::vec3 centre = (glm::vec3(i, j, k) + 0.5f) * g.cellSize;
                const bool inside = glm::distance(centre, glm::vec3(ball.endA)) < ball.endA.w;
                EXPECT_EQ(access.getValue(openvdb::Coord{int(i), int(j), int(k)}),
                          inside ? 1.0f : 0.0f)
                    << i << " " << j << " " << k;
            }

    fluid::VdbFrame plain;
    plain.state = &s;
    const std::string plainPath = outputPath("no_solid.vdb");
    ASSERT_TRUE(fluid::writeVdb(plainPath, plain).ok());
    EXPECT_FALSE(named<openvdb::FloatGrid>(readAll(plainPath), "solid"));
}

TEST(VdbExport, AFileThatCannotBeWrittenIsOneErrorNamingIt) {
    const GridShape g{8, 8, 8, 0.1f};
    const FieldState s = FieldState::zero(g);
    fluid::VdbFrame frame;
    frame.state = &s;
    const std::string path = outputPath("no_such_dir/x.vdb");
    const Status written = fluid::writeVdb(path, frame);
    ASSERT_FALSE(written.ok());
    EXPECT_NE(written.error().message.find(path), std::string::npos) << written.error().message;
}

using VdbSceneTest = GpuTest;

// The first 4 frames of a scene (`smoke`: its one smoke effect's keys), each frame's files written
// through the commands' writer into `out`.
std::unique_ptr<sim::SceneSimulation> runWritingVdbs(const gpu::Context& ctx,
                                                     const std::string& smoke,
                                                     const anim::Character& fighter,
                                                     app::VdbOutput& out) {
    const scene::Scene s = parseScene(R"({"character": {"clip": "roundhouse_kick"},
        "output": {"fps": 30, "frames": 4}, "effects": [{"type": "smoke", )" +
                                      smoke + "}]}");
    auto sim = simulate(ctx, s, fighter);
    if (!sim) return nullptr;
    out.on = true;
    out.dir = std::string(MFX_TEST_OUTPUT_DIR) + "/vdb";
    std::filesystem::create_directories(out.dir);
    for (uint32_t f = 0; f < 4; ++f) {
        sim->runFrame(f);
        EXPECT_TRUE(app::writeFrameVdbs(*sim, f, out).ok());
    }
    return sim;
}

// A scene's smoke, frame by frame through the commands' writer: each file holds its grid's state
// where the grid stands in the world.
TEST_F(VdbSceneTest, EachFramesFileHoldsTheGridsStateWhereTheGridStands) {
    const anim::Character fighter = anim::makeFighter();
    app::VdbOutput out;
    // Without the body's solid grid (its own test is above).
    auto sim = runWritingVdbs(ctx(), R"("name": "kick_smoke", "bones": ["foot_r"],
        "grid": [16, 16, 16], "cell_size": 0.1, "collide": false)",
                              fighter, out);
    ASSERT_TRUE(sim);
    EXPECT_EQ(out.files, 4u);
    fluid::SmokeGrid& grid = sim->smokeGrids()[0].grid;
    const FieldState s = grid.state();
    expectFileHolds(
        out.dir + "/kick_smoke_0003.vdb", s, grid.origin(), [](glm::vec3 p) { return p; },
        [](glm::uvec3) { return true; });
}

// The same for a sparse scene grid: its files hold the stored cells alone, with the values its
// atlas holds there (without the body, whose bricks would fill this small domain).
TEST_F(VdbSceneTest, ASparseGridsFilesHoldItsStoredCells) {
    const anim::Character fighter = anim::makeFighter();
    app::VdbOutput out;
    auto sim = runWritingVdbs(ctx(), R"("name": "sparse_smoke", "bones": ["foot_r"],
        "domain": "sparse", "grid": [32, 32, 32], "cell_size": 0.1, "collide": false)",
                              fighter, out);
    ASSERT_TRUE(sim);
    fluid::SmokeGrid& grid = sim->smokeGrids()[0].grid;
    ASSERT_TRUE(grid.sparse());
    const FieldState s = grid.state();
    const std::vector<uint8_t> stored = grid.storedCells();
    const size_t storedCount = size_t(std::count(stored.begin(), stored.end(), uint8_t(1)));
    EXPECT_GT(storedCount, 0u);
    EXPECT_LT(storedCount, stored.size());
    const GridShape& g = grid.options().grid;
    expectFileHolds(
        out.dir + "/sparse_smoke_0003.vdb", s, grid.origin(), [](glm::vec3 p) { return p; },
        [&](glm::uvec3 q) { return stored[g.index(q.x, q.y, q.z)] != 0; });
}

TEST(VdbCli, ABadUpAxisIsOneErrorLine) {
    const RunResult r = runMotionfx("simulate --frames 1 --vdb-up x --vdb out_vdb");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("--vdb-up must be y or z"), std::string::npos) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
}

} // namespace
} // namespace mfx::test
