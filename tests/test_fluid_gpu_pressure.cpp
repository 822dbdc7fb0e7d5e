// The GPU pressure solvers beyond Jacobi (fluid/gpu_multigrid.h): red-black Gauss-Seidel,
// multigrid V-cycles and MGPCG, each against the CPU reference from the same input (relative L2
// of the pressure at most 1e-5, fp32 against fp64), on an even and an odd non-cubic grid with every
// boundary set; the multigrid's convergence rate and MGPCG's iteration count at the sizes the
// requirements name; and 100 whole steps of a scenario with each solver.
#include "fluid/field_compare.h"
#include "fluid/reference/reference_solver.h"
#include "fluid/scenarios.h"
#include "fluid/smoke_solver.h"
#include "tests/fluid_side_by_side.h"
#include "tests/fluid_test_util.h"
#include "tests/gpu_test.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <string>
#include <vector>

namespace mfx::test {
namespace {

// A smooth velocity field (low Fourier modes, no symmetry) far from divergence-free, with its
// divergence (boundaries applied first, as a step does): the right-hand side multigrid's
// convergence rate is quoted for (the same field as test_fluid_accuracy_pressure.cpp's).
FieldState smoothDivergence(const SolverOptions& options) {
    FieldState s = smoothState(options.grid);
    fluid::ReferenceSolver cpu(options);
    cpu.setState(s);
    cpu.applyBoundaries();
    cpu.computeDivergence();
    return cpu.state();
}

// ||b - A p|| / ||b|| of `state`'s pressure for its divergence, in double (the reference's
// measure).
double relativeResidual(const SolverOptions& options, const FieldState& state) {
    fluid::ReferenceSolver cpu(options);
    cpu.setState(state);
    return cpu.pressureResidual();
}

class GpuPressureTest : public GpuTest {
public:
    // One solvePressure on the GPU and on the reference from `input`; returns the relative L2
    // difference of the pressure (and checks that the solve moved it).
    double solveBoth(const SolverOptions& options, const FieldState& input,
                     uint32_t* gpuIterations = nullptr, uint32_t* cpuIterations = nullptr,
                     FieldState* gpuState = nullptr) {
        const StageSideBySide run =
            runStageSideBySide(ctx(), options, input, fluid::Stage::SolvePressure);
        if (!run.ok) return 1.0;
        if (gpuIterations) *gpuIterations = run.gpuIterations;
        if (cpuIterations) *cpuIterations = run.cpuIterations;
        EXPECT_GT(fluid::difference(run.cpu, input).pressure.relL2, 1e-3)
            << "the solve left the pressure as it was";
        if (gpuState) *gpuState = run.gpu;
        return pressureDifference(options, run.gpu, run.cpu);
    }

    // The relative L2 difference of two pressures. Without an open face the pressure is defined
    // up to a constant (A's null space), which neither solver controls: rounding moves it by a
    // random walk (in a 37x22x19 periodic box, 8e-6 relative after two V-cycles, while the
    // pressures less their means agree to 2e-7). There each pressure's mean is removed first.
    static double pressureDifference(const SolverOptions& options, const FieldState& gpu,
                                     const FieldState& cpu) {
        const bool singular =
            std::none_of(options.boundaries.begin(), options.boundaries.end(),
                         [](const fluid::FaceBoundary& f) { return f.kind == Boundary::Open; });
        auto mean = [&](const std::vector<float>& p) {
            double sum = 0.0;
            for (float v : p)
                sum += double(v);
            return singular && !p.empty() ? sum / double(p.size()) : 0.0;
        };
        const double gpuMean = mean(gpu.pressure), cpuMean = mean(cpu.pressure);
        double difference = 0.0, norm = 0.0;
        for (size_t i = 0; i < cpu.pressure.size(); ++i) {
            const double c = double(cpu.pressure[i]) - cpuMean;
            const double d = double(gpu.pressure[i]) - gpuMean - c;
            difference += d * d;
            norm += c * c;
        }
        return norm > 0.0 ? std::sqrt(difference / norm) : std::sqrt(difference);
    }
};

// The solvers' variants: odd and even sweep counts, cold and warm starts.
struct Variant {
    const char* name;
    void (*apply)(SolverOptions&);
    // The random start pressure (warm start) scaled by h², to the solution's size. A start some
    // hundred times the solution, as randomState's, makes the conjugate gradient's result the
    // difference of two large vectors: fp32 and fp64 then part by up to 5e-5 in MGPCG's first
    // iterations, where they part by 1e-6 at most from a start of the solution's size.
    bool startOfSolutionSize = false;
};

// An even grid and an odd non-cubic one. On both, level 0 is smoothed, restricted and prolonged
// by dispatches over the whole level and the coarser levels cycle in one workgroup
// (cycle_coarse_levels); the small grids of the tests below cycle every level in one workgroup.
constexpr GridShape kEvenGrid{24, 20, 16, 0.05f};
constexpr GridShape kOddGrid{37, 22, 19, 0.05f};

void matchesReference(GpuPressureTest& test, const GridShape& grid, PressureSolver solver,
                      std::span<const Variant> variants) {
    uint32_t seed = 700 + grid.cellsX;
    for (Boundaries b : kAllBoundaries)
        for (const Variant& variant : variants) {
            SolverOptions options = pressureOptions(grid, b, solver);
            variant.apply(options);
            FieldState input = randomState(grid, ++seed);
            if (variant.startOfSolutionSize)
                for (float& p : input.pressure)
                    p *= grid.cellSize * grid.cellSize;
            const double d = test.solveBoth(options, input);
            EXPECT_LE(d, 1e-5) << grid.cellsX << "x" << grid.cellsY << "x" << grid.cellsZ << " "
                               << boundariesName(b) << " " << variant.name;
        }
}

// =================================================================================================
// GPU against the reference, from the same input
// =================================================================================================

const Variant kRedBlackVariants[] = {
    {"3 sweeps cold", [](SolverOptions& o) { o.jacobiIterations = 3; }},
    {"4 sweeps warm", [](SolverOptions& o) {
         o.jacobiIterations = 4;
         o.warmStart = true;
     }}};

const Variant kMultigridVariants[] = {
    {"2 cycles 2+2 cold",
     [](SolverOptions& o) {
         o.multigrid.cycles = 2;
         o.multigrid.preSmooth = 2;
         o.multigrid.postSmooth = 2;
     }},
    {"1 cycle 1+3 warm",
     [](SolverOptions& o) {
         o.multigrid.cycles = 1;
         o.multigrid.preSmooth = 1;
         o.multigrid.postSmooth = 3;
         o.warmStart = true;
     }},
    // The GPU's restriction, which computes the residual.
    {"2 cycles 2+2 cold, residual in restriction",
     [](SolverOptions& o) {
         o.multigrid.cycles = 2;
         o.multigrid.residualInRestriction = fluid::ByDevice::On;
     }},
    {"1 cycle 1+3 warm, residual in restriction", [](SolverOptions& o) {
         o.multigrid.cycles = 1;
         o.multigrid.preSmooth = 1;
         o.multigrid.postSmooth = 3;
         o.warmStart = true;
         o.multigrid.residualInRestriction = fluid::ByDevice::On;
     }}};

// A tolerance of 0 runs exactly cgMaxIterations iterations on both sides (a stop on a
// tolerance is checked on its own below: near the tolerance, fp32 and fp64 could stop one
// iteration apart).
const Variant kMgpcgVariants[] = {{"3 iterations, 2+2 sweeps, cold",
                                   [](SolverOptions& o) {
                                       o.cgTolerance = 0.0f;
                                       o.cgMaxIterations = 3;
                                   }},
                                  {"2 iterations, 1+1 sweeps, warm",
                                   [](SolverOptions& o) {
                                       o.cgTolerance = 0.0f;
                                       o.cgMaxIterations = 2;
                                       o.multigrid.preSmooth = 1;
                                       o.multigrid.postSmooth = 1;
                                       o.warmStart = true;
                                   },
                                   true}};

TEST_F(GpuPressureTest, RedBlackMatchesReferenceEvenGrid) {
    matchesReference(*this, kEvenGrid, PressureSolver::RedBlackGaussSeidel, kRedBlackVariants);
}

TEST_F(GpuPressureTest, RedBlackMatchesReferenceOddGrid) {
    matchesReference(*this, kOddGrid, PressureSolver::RedBlackGaussSeidel, kRedBlackVariants);
}

TEST_F(GpuPressureTest, MultigridMatchesReferenceEvenGrid) {
    matchesReference(*this, kEvenGrid, PressureSolver::Multigrid, kMultigridVariants);
}

TEST_F(GpuPressureTest, MultigridMatchesReferenceOddGrid) {
    matchesReference(*this, kOddGrid, PressureSolver::Multigrid, kMultigridVariants);
}

// A grid whose level 1 is odd and dispatched over the whole level (300 bricks): its cells halve
// with a lone first cell (Multigrid's constructor), so R0's coarse bricks do not start on a
// fine brick, and a restriction that computes the residual computes it over the shifted range.
TEST_F(GpuPressureTest, MultigridMatchesReferenceShiftedLevel) {
    constexpr GridShape grid{74, 44, 38, 0.05f};
    uint32_t seed = 900;
    for (fluid::ByDevice fused : {fluid::ByDevice::Off, fluid::ByDevice::On})
        for (Boundaries b : {Boundaries::Mixed, Boundaries::Periodic}) {
            SolverOptions options = pressureOptions(grid, b, PressureSolver::Multigrid);
            options.multigrid.cycles = 1;
            options.multigrid.residualInRestriction = fused;
            const double d = solveBoth(options, randomState(grid, ++seed));
            EXPECT_LE(d, 1e-5) << boundariesName(b) << " residual in restriction "
                               << (fused == fluid::ByDevice::On ? "on" : "off");
        }
}

TEST_F(GpuPressureTest, MgpcgMatchesReferenceEvenGrid) {
    matchesReference(*this, kEvenGrid, PressureSolver::MultigridPcg, kMgpcgVariants);
}

TEST_F(GpuPressureTest, MgpcgMatchesReferenceOddGrid) {
    matchesReference(*this, kOddGrid, PressureSolver::MultigridPcg, kMgpcgVariants);
}

// A hierarchy cut short by multigrid.levels: the coarsest level is larger (up to 480 cells here)
// and still solved exactly, by both V-cycles.
TEST_F(GpuPressureTest, FewerLevelsMatchReference) {
    uint32_t seed = 800;
    for (PressureSolver solver : {PressureSolver::Multigrid, PressureSolver::MultigridPcg})
        for (uint32_t levels : {2u, 3u}) {
            // 2 levels: a coarsest level of 12x10x4 = 480 cells.
            const GridShape grid{24, 20, 8, 0.05f};
            SolverOptions options = pressureOptions(grid, Boundaries::Mixed, solver);
            options.multigrid.levels = levels;
            options.multigrid.cycles = 2;
            options.cgTolerance = 0.0f;
            options.cgMaxIterations = 2;
            const double d = solveBoth(options, randomState(grid, ++seed));
            EXPECT_LE(d, 1e-5) << fluid::pressureSolverName(solver) << ", " << levels << " levels";
        }
}

// A coarsest level too large to solve exactly is refused with a reason naming the option.
TEST_F(GpuPressureTest, TooLargeCoarsestLevelIsRefused) {
    SolverOptions options =
        pressureOptions({32, 32, 32, 1.0f / 32}, Boundaries::Walls, PressureSolver::Multigrid);
    options.multigrid.levels = 2;
    auto created = fluid::SmokeSolver::create(ctx(), options);
    ASSERT_FALSE(created.ok());
    EXPECT_NE(created.error().message.find("levels"), std::string::npos) << created.error().message;
}

// Grids with axes of 1, 2 or 3 cells (a cell its own periodic neighbour, a level that cannot be
// halved, a hierarchy of one level whose only level is solved exactly): every solver still
// matches.
void degenerateGridsMatch(GpuPressureTest& test, PressureSolver solver) {
    const GridShape grids[] = {
        {1, 1, 1, 0.1f}, {2, 1, 1, 0.1f}, {1, 3, 1, 0.1f}, {3, 2, 1, 0.1f}, {5, 1, 7, 0.1f}};
    uint32_t seed = 900;
    for (const GridShape& grid : grids)
        for (Boundaries b : {Boundaries::Walls, Boundaries::Periodic, Boundaries::Mixed}) {
            SolverOptions options = pressureOptions(grid, b, solver);
            options.jacobiIterations = 3;
            options.cgTolerance = 0.0f;
            options.cgMaxIterations = 2;
            // A 1x1x1 box of walls solves to 0 on both sides: then the difference is absolute.
            EXPECT_LE(test.solveBoth(options, randomState(grid, ++seed)), 1e-5)
                << grid.cellsX << "x" << grid.cellsY << "x" << grid.cellsZ << " "
                << boundariesName(b);
        }
}

TEST_F(GpuPressureTest, RedBlackDegenerateGridsMatchReference) {
    degenerateGridsMatch(*this, PressureSolver::RedBlackGaussSeidel);
}

TEST_F(GpuPressureTest, MultigridDegenerateGridsMatchReference) {
    degenerateGridsMatch(*this, PressureSolver::Multigrid);
}

TEST_F(GpuPressureTest, MgpcgDegenerateGridsMatchReference) {
    degenerateGridsMatch(*this, PressureSolver::MultigridPcg);
}

// MGPCG stopping on its tolerance: the GPU stops within one iteration of the reference,
// below the tolerance (measured in double from the GPU's pressure; CG's own fp32 residual
// decides, hence the 5 % margin).
TEST_F(GpuPressureTest, MgpcgStopsOnItsTolerance) {
    for (Boundaries b : kAllBoundaries)
        for (float tolerance : {1e-2f, 1e-4f}) {
            SolverOptions options =
                pressureOptions({13, 7, 9, 0.125f}, b, PressureSolver::MultigridPcg);
            options.cgTolerance = tolerance;
            options.cgMaxIterations = 30;
            const FieldState input = randomState(options.grid, 77);
            uint32_t gpuIterations = 0, cpuIterations = 0;
            FieldState solved;
            solveBoth(options, input, &gpuIterations, &cpuIterations, &solved);
            const double residual = relativeResidual(options, solved);
            std::printf("  %-8s tolerance %.0e: GPU %u iterations (residual %.3g), reference %u\n",
                        boundariesName(b), double(tolerance), gpuIterations, residual,
                        cpuIterations);
            EXPECT_LE(residual, 1.05 * double(tolerance)) << boundariesName(b);
            EXPECT_LE(gpuIterations, cpuIterations + 1) << boundariesName(b);
            EXPECT_GE(gpuIterations + 1, cpuIterations) << boundariesName(b);
        }
}

// Without a right-hand side (no divergence) MGPCG's solution is 0, as the reference's.
TEST_F(GpuPressureTest, MgpcgWithoutRightHandSideGivesZero) {
    SolverOptions options =
        pressureOptions({8, 6, 5, 0.1f}, Boundaries::Walls, PressureSolver::MultigridPcg);
    options.warmStart = true;
    FieldState input = randomState(options.grid, 5);
    std::fill(input.divergence.begin(), input.divergence.end(), 0.0f);
    auto created = fluid::SmokeSolver::create(ctx(), options);
    ASSERT_TRUE(created.ok());
    created.value()->setState(input);
    created.value()->runStage(fluid::Stage::SolvePressure);
    for (float p : created.value()->state().pressure)
        ASSERT_EQ(p, 0.0f);
}

// =================================================================================================
// Convergence at the sizes the requirements name
// =================================================================================================

// The GPU multigrid's residual after each of `cycles` V-cycles (2 + 2 sweeps, the full
// hierarchy) on the smooth divergence: one warm-started one-cycle solve per cycle, which
// continues the previous solve's cycles exactly (the right-hand side does not change).
std::vector<double> gpuMultigridResiduals(const gpu::Context& ctx, Boundaries b, GridShape grid,
                                          uint32_t cycles) {
    SolverOptions options = pressureOptions(grid, b, PressureSolver::Multigrid);
    options.multigrid.cycles = 1;
    options.warmStart = true;
    const FieldState input = smoothDivergence(options);
    auto created = fluid::SmokeSolver::create(ctx, options);
    EXPECT_TRUE(created.ok()) << created.error().message;
    if (!created.ok()) return {};
    fluid::SmokeSolver& gpu = *created.value();
    gpu.setState(input);
    std::vector<double> residuals{relativeResidual(options, input)};
    for (uint32_t c = 0; c < cycles; ++c) {
        gpu.runStage(fluid::Stage::SolvePressure);
        residuals.push_back(relativeResidual(options, gpu.state()));
    }
    std::printf("  %ux%ux%u %s: residual", grid.cellsX, grid.cellsY, grid.cellsZ,
                boundariesName(b));
    for (double r : residuals)
        std::printf(" %.3g", r);
    std::printf("\n");
    return residuals;
}

void expectFivefold(const gpu::Context& ctx, Boundaries b, GridShape grid, uint32_t cycles) {
    const std::vector<double> r = gpuMultigridResiduals(ctx, b, grid, cycles);
    ASSERT_EQ(r.size(), cycles + 1);
    for (size_t i = 1; i < r.size(); ++i)
        EXPECT_GE(r[i - 1] / r[i], 5.0) << boundariesName(b) << " cycle " << i;
}

TEST_F(GpuPressureTest, MultigridFivefoldPerCycle32) {
    for (Boundaries b : kAllBoundaries)
        expectFivefold(ctx(), b, {32, 32, 32, 1.0f / 32}, 3);
}

TEST_F(GpuPressureTest, MultigridFivefoldPerCycle64) {
    for (Boundaries b : {Boundaries::Walls, Boundaries::Mixed})
        expectFivefold(ctx(), b, {64, 64, 64, 1.0f / 64}, 3);
}

// Values of `b` that differ from `a`'s in any bit of their float (all of them when the sizes
// differ).
size_t differingValues(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size()) return std::max(a.size(), b.size());
    size_t differing = 0;
    for (size_t i = 0; i < a.size(); ++i)
        differing += a[i] != b[i] ? 1 : 0;
    return differing;
}

// Solver options SmokeSolver::create refuses with a message holding `text`.
void expectRefused(const gpu::Context& ctx, const SolverOptions& options, const std::string& text) {
    auto created = fluid::SmokeSolver::create(ctx, options);
    ASSERT_FALSE(created.ok()) << text;
    EXPECT_NE(created.error().message.find(text), std::string::npos) << created.error().message;
}

// The workgroup that cycles the coarse levels (MultigridOptions::coarseGroup: 8 on a CPU device,
// 64 on a GPU) shares out the same bricks' work among its invocations: any size gives the same
// bits, for the multigrid solver's cycle and MGPCG's.
TEST_F(GpuPressureTest, CoarseGroupSizeDoesNotChangeTheSolution) {
    struct Case {
        PressureSolver solver;
        Boundaries boundaries;
        std::vector<uint32_t> groups; // the first is the reference of the others
    };
    const Case cases[] = {{PressureSolver::Multigrid, Boundaries::Mixed, {8, 13, 64}},
                          {PressureSolver::MultigridPcg, Boundaries::Periodic, {8, 64}}};
    for (const Case& c : cases) {
        SolverOptions options = pressureOptions(kOddGrid, c.boundaries, c.solver);
        options.cgTolerance = 0.0f;
        options.cgMaxIterations = 2;
        const FieldState input = randomState(kOddGrid, 97);
        std::vector<float> first;
        for (uint32_t group : c.groups) {
            options.multigrid.coarseGroup = group;
            FieldState gpu;
            solveBoth(options, input, nullptr, nullptr, &gpu);
            ASSERT_EQ(gpu.pressure.size(), input.pressure.size());
            if (first.empty()) {
                first = gpu.pressure;
                continue;
            }
            EXPECT_EQ(differingValues(first, gpu.pressure), 0u)
                << fluid::pressureSolverName(c.solver) << " " << boundariesName(c.boundaries)
                << " group " << group;
        }
    }
}

// The brick one invocation handles (MultigridOptions::brick: 4 rows and layers on a CPU device,
// 1 on a GPU) changes which invocation does a cell's work, not the work: on the odd grid (partial
// bricks along y and z; its 19x11x10 level 1 cycled in one workgroup) every brick size matches
// the reference, and the multigrid and red-black solvers' results are the same bits whatever the
// brick (MGPCG's dot products are summed per workgroup, so their rounding follows the dispatch).
TEST_F(GpuPressureTest, BrickSizeDoesNotChangeTheSolution) {
    struct Case {
        PressureSolver solver;
        Boundaries boundaries;
        std::vector<uint32_t> bricks; // the first is the reference of the others
        bool sameBits;
    };
    const Case cases[] = {{PressureSolver::Multigrid, Boundaries::Mixed, {4, 2, 1}, true},
                          {PressureSolver::RedBlackGaussSeidel, Boundaries::Periodic, {4, 1}, true},
                          {PressureSolver::MultigridPcg, Boundaries::Walls, {4, 1}, false}};
    uint32_t seed = 300;
    for (const Case& c : cases) {
        SolverOptions options = pressureOptions(kOddGrid, c.boundaries, c.solver);
        options.jacobiIterations = 4;
        options.cgTolerance = 0.0f;
        options.cgMaxIterations = 2;
        const FieldState input = randomState(kOddGrid, ++seed);
        std::vector<float> first;
        for (uint32_t brick : c.bricks) {
            options.multigrid.brick = brick;
            FieldState gpu;
            const double d = solveBoth(options, input, nullptr, nullptr, &gpu);
            const std::string name = std::string(fluid::pressureSolverName(c.solver)) + " " +
                                     boundariesName(c.boundaries) + " brick " +
                                     std::to_string(brick);
            EXPECT_LE(d, 1e-5) << name;
            if (first.empty()) {
                first = gpu.pressure;
                continue;
            }
            if (!c.sameBits) continue;
            ASSERT_EQ(gpu.pressure.size(), first.size());
            EXPECT_EQ(differingValues(first, gpu.pressure), 0u) << name;
        }
    }
}

// Where the one-workgroup coarse cycle starts (MultigridOptions::coarseCells) moves levels between
// that cycle and separate dispatches, which run the same functions: the same bits whichever
// (the even grid's 24x20x16 hierarchy: levels of 960, 120 and fewer cells).
TEST_F(GpuPressureTest, WhereTheCoarseCycleStartsDoesNotChangeTheSolution) {
    for (PressureSolver solver : {PressureSolver::Multigrid, PressureSolver::MultigridPcg}) {
        SolverOptions options = pressureOptions(kEvenGrid, Boundaries::Mixed, solver);
        options.cgTolerance = 0.0f;
        options.cgMaxIterations = 2;
        const FieldState input = randomState(kEvenGrid, 77);
        std::vector<float> first;
        for (uint32_t cells : {4096u, 512u, 8u}) {
            options.multigrid.coarseCells = cells;
            FieldState gpu;
            const double d = solveBoth(options, input, nullptr, nullptr, &gpu);
            const std::string name =
                std::string(fluid::pressureSolverName(solver)) + " from " + std::to_string(cells);
            EXPECT_LE(d, 1e-5) << name;
            if (first.empty()) {
                first = gpu.pressure;
                continue;
            }
            EXPECT_EQ(differingValues(first, gpu.pressure), 0u) << name;
        }
    }
    // And it does move them: a step's pressure dispatches grow as the cycle starts lower.
    uint32_t previous = 0;
    for (uint32_t cells : {4096u, 512u, 8u}) {
        SolverOptions options =
            pressureOptions(kEvenGrid, Boundaries::Mixed, PressureSolver::Multigrid);
        options.multigrid.coarseCells = cells;
        auto solver = fluid::SmokeSolver::create(ctx(), options);
        ASSERT_TRUE(solver.ok()) << solver.error().message;
        solver.value()->setState(randomState(kEvenGrid, 78));
        solver.value()->step();
        uint32_t dispatches = 0;
        for (const auto& [stage, count] : solver.value()->lastStepDispatches())
            if (stage == "solve_pressure") dispatches = count;
        EXPECT_GT(dispatches, previous) << "from " << cells << " cells";
        previous = dispatches;
    }
    SolverOptions tooMany =
        pressureOptions(kEvenGrid, Boundaries::Mixed, PressureSolver::Multigrid);
    tooMany.multigrid.coarseCells = 8192;
    expectRefused(ctx(), tooMany, "coarseCells 8192 must be at most 4096");
}

TEST_F(GpuPressureTest, ABrickOtherThanOneTwoOrFourIsRefused) {
    SolverOptions options = pressureOptions(kOddGrid, Boundaries::Walls, PressureSolver::Multigrid);
    options.multigrid.brick = 3;
    expectRefused(ctx(), options, "multigrid brick 3 must be 1, 2 or 4");
}

// 1e-3 at 64^3 on the smooth divergence within the reference's iteration count plus one:
// the GPU runs with cgMaxIterations set to that, and its pressure's residual is measured in
// double.
TEST_F(GpuPressureTest, MgpcgReachesOneThousandthAt64) {
    for (Boundaries b : {Boundaries::Walls, Boundaries::Mixed}) {
        SolverOptions options =
            pressureOptions({64, 64, 64, 1.0f / 64}, b, PressureSolver::MultigridPcg);
        options.cgTolerance = 1e-3f;
        options.cgMaxIterations = 50;
        const FieldState input = smoothDivergence(options);
        fluid::ReferenceSolver cpu(options);
        cpu.setState(input);
        cpu.solvePressure();
        const uint32_t referenceIterations = cpu.pressureIterations();
        options.cgMaxIterations = referenceIterations + 1;
        auto created = fluid::SmokeSolver::create(ctx(), options);
        ASSERT_TRUE(created.ok()) << created.error().message;
        fluid::SmokeSolver& gpu = *created.value();
        gpu.setState(input);
        gpu.runStage(fluid::Stage::SolvePressure);
        const double residual = relativeResidual(options, gpu.state());
        std::printf("  %s: GPU %u iterations, residual %.3g; reference %u iterations\n",
                    boundariesName(b), gpu.lastPressureIterations(), residual, referenceIterations);
        EXPECT_LE(residual, 1e-3) << boundariesName(b);
        EXPECT_LE(gpu.lastPressureIterations(), referenceIterations + 1) << boundariesName(b);
    }
}

// =================================================================================================
// Whole steps
// =================================================================================================

// 100 steps of the puff scenario at 16^3 with each solver, GPU against the reference from the same
// start. The bound is test_fluid_steps.cpp's for Jacobi (fp32 against fp64, the rounding of 11
// stages accumulated over 100 steps; 1e-4 is ten times below what a wrong stage gives). Measured
// on lavapipe: at most 2.2e-5 (the divergence, a difference of nearly equal face values), 4e-6 in
// pressure, for every solver.
class GpuPressureStepsTest : public GpuTest,
                             public ::testing::WithParamInterface<PressureSolver> {};

TEST_P(GpuPressureStepsTest, HundredStepsStayCloseToReference) {
    SideBySide run;
    runSideBySide(
        ctx(), "puff", {16, 16, 16}, 100, [&](SolverOptions& o) { o.pressureSolver = GetParam(); },
        run);
    if (HasFatalFailure()) return;
    printDifference(fluid::pressureSolverName(GetParam()), run.difference);
    expectClose(run.difference, 1e-4, "100 steps");
    expectMovingAndFinite(run);
}

INSTANTIATE_TEST_SUITE_P(GpuPressure, GpuPressureStepsTest,
                         ::testing::Values(PressureSolver::RedBlackGaussSeidel,
                                           PressureSolver::Multigrid, PressureSolver::MultigridPcg),
                         [](const auto& param) {
                             return std::string(fluid::pressureSolverName(param.param));
                         });

} // namespace
} // namespace mfx::test
