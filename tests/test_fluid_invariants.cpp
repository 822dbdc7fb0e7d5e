// Invariants of the smoke solver's projection and pigment advection that hold whatever the input,
// checked on the GPU solver (SmokeSolver, fp32) and on the CPU reference (ReferenceSolver, fp64)
// alike (those of whole steps are in test_fluid_invariants_evolution.cpp):
//
//   * the exact pressure solve leaves a discretely divergence-free field;
//   * more Jacobi sweeps leave less divergence, for odd and even sweep counts;
//   * semi-Lagrangian pigment advection creates no new extrema (maximum principle).
#include "fluid/reference/reference_solver.h"
#include "fluid/smoke_solver.h"
#include "tests/fluid_invariant_util.h"
#include "tests/fluid_test_util.h"
#include "tests/gpu_test.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

namespace mfx::test {
namespace {

// --- Helpers ------------------------------------------------------------------------------------

double rms(std::span<const float> values) {
    double sum = 0.0;
    for (float v : values)
        sum += double(v) * double(v);
    return values.empty() ? 0.0 : std::sqrt(sum / double(values.size()));
}

// Velocities scaled by `scale` (the random state has them in [-1, 1]).
FieldState scaledVelocity(FieldState s, float scale) {
    for (int c = 0; c < 3; ++c)
        for (float& v : component(s, c))
            v *= scale;
    return s;
}

// Runs `stages` in order on the GPU solver (each submitted and waited for).
void runGpuStages(fluid::SmokeSolver& gpu, std::initializer_list<fluid::Stage> stages) {
    for (fluid::Stage stage : stages)
        gpu.runStage(stage);
}

// The stages of a projection, with the divergence recomputed after it.
constexpr std::initializer_list<fluid::Stage> kProjectAndMeasure = {
    fluid::Stage::ApplyBoundaries, fluid::Stage::ComputeDivergence,
    fluid::Stage::SolvePressure,   fluid::Stage::Project,
    fluid::Stage::ApplyBoundaries, fluid::Stage::ComputeDivergence};

// Divergence of `input` (after applyBoundaries), as the reference computes it.
std::vector<float> initialDivergence(const SolverOptions& options, const FieldState& input) {
    fluid::ReferenceSolver cpu(options);
    cpu.setState(input);
    cpu.applyBoundaries();
    cpu.computeDivergence();
    return cpu.state().divergence;
}

// =================================================================================================
// 1. The exact projection (CPU): the divergence left after projecting with the pressure of
// solvePressureExact is the residual of its conjugate gradient solve, stopped at 1e-12 relative
// residual. In norms: max_after <= L2_after <= 1e-12 L2_before <= 1e-12 sqrt(cells) max_before
// ~ 3e-11 max_before on these ~1000-cell grids; the bound 1e-6 leaves ample room and still fails
// for any projection whose gradient does not match the divergence (a wrong sign, a boundary face
// treated differently by solve and projection).
// =================================================================================================

struct ProjectionResult {
    double before = 0.0;
    double after = 0.0;
};

ProjectionResult projectExactly(const SolverOptions& options, const FieldState& input) {
    fluid::ReferenceSolver cpu(options);
    cpu.setState(input);
    cpu.applyBoundaries();
    cpu.computeDivergence();
    ProjectionResult r;
    r.before = maxAbs(cpu.state().divergence);
    cpu.solvePressureExact();
    cpu.project();
    cpu.applyBoundaries();
    cpu.computeDivergence();
    // The divergence field is computed in double and only then rounded to float: small values
    // keep their relative precision (computeDiagnostics would difference float velocities and
    // floor the measurement at ~1e-7 of the face speeds).
    r.after = maxAbs(cpu.state().divergence);
    return r;
}

void expectExactProjection(const SolverOptions& options, const FieldState& input) {
    const ProjectionResult r = projectExactly(options, input);
    ASSERT_GT(r.before, 1.0) << "the input must start far from divergence-free";
    std::printf("  max |div| before %.6g, after %.3g (ratio %.3g)\n", r.before, r.after,
                r.after / r.before);
    EXPECT_LE(r.after, 1e-6 * r.before) << "max |div| before " << r.before << ", after " << r.after;
}

TEST(FluidInvariantExactProjection, RandomFieldClosedBox) {
    const SolverOptions options = closedBoxOptions();
    expectExactProjection(options, randomState(options.grid, 11));
}

TEST(FluidInvariantExactProjection, RandomFieldMixedBoundaries) {
    const SolverOptions options = mixedBoundaryOptions();
    expectExactProjection(options, randomState(options.grid, 12));
}

TEST(FluidInvariantExactProjection, SmoothFieldClosedBox) {
    const SolverOptions options = closedBoxOptions();
    expectExactProjection(options, smoothState(options.grid));
}

TEST(FluidInvariantExactProjection, SmoothFieldMixedBoundaries) {
    const SolverOptions options = mixedBoundaryOptions();
    expectExactProjection(options, smoothState(options.grid));
}

// The Diagnostics path agrees: computeDiagnostics on the projected state (float velocities) sees
// the divergence drop by at least 1e4. Its floor is float rounding of the face velocities
// (~6e-8 * |u| / h per face difference, |u| ~ 1, h = 0.125), against a max divergence before of
// ~10: 1e-4 leaves two orders of margin above that floor.
TEST(FluidInvariantExactProjection, DiagnosticsSeeDivergenceRemoved) {
    const SolverOptions options = closedBoxOptions();
    fluid::ReferenceSolver cpu(options);
    cpu.setState(randomState(options.grid, 13));
    cpu.applyBoundaries();
    const double before = fluid::computeDiagnostics(options, cpu.state()).maxDivergence;
    cpu.computeDivergence();
    cpu.solvePressureExact();
    cpu.project();
    cpu.applyBoundaries();
    const double after = fluid::computeDiagnostics(options, cpu.state()).maxDivergence;
    std::printf("  diagnostics max |div| before %.6g, after %.3g\n", before, after);
    ASSERT_GT(before, 1.0);
    EXPECT_LE(after, 1e-4 * before) << "before " << before << ", after " << after;
}

// =================================================================================================
// 2. Jacobi convergence: the divergence left after projecting with N cold-started sweeps is, up to
// a factor -1/h^2, the residual of the pressure equation after N sweeps: r_N = (A D^-1)^N r_0,
// with A the neighbour sum and D the neighbour counts. A D^-1 is similar to the symmetric
// D^-1/2 A D^-1/2, whose eigenvalues lie in [-1, 1] (in (-1, 1) with an open face), so every sweep
// shrinks the residual's D^-1-weighted norm; on these random inputs the plain RMS shrinks as well,
// and a sweep count that leaves as much divergence as a smaller one (a sweep lost or repeated in
// the ping-pong, a result left in the wrong image for odd or even counts) fails. Measured as RMS
// divergence. (In the closed box, a bipartite grid with no open face, -1 is an eigenvalue: the
// residual's checkerboard component never decays, so the sequence levels off above 0 but still
// decreases.)
// =================================================================================================

const std::vector<uint32_t> kSweepCounts = {1, 2, 3, 4, 7, 8, 15, 16, 31, 32};

double remainingDivergenceCpu(SolverOptions options, uint32_t sweeps, const FieldState& input) {
    options.jacobiIterations = sweeps;
    options.warmStart = false;
    fluid::ReferenceSolver cpu(options);
    cpu.setState(input);
    cpu.applyBoundaries();
    cpu.computeDivergence();
    cpu.solvePressure();
    cpu.project();
    cpu.applyBoundaries();
    cpu.computeDivergence();
    return rms(cpu.state().divergence);
}

double remainingDivergenceGpu(const gpu::Context& ctx, SolverOptions options, uint32_t sweeps,
                              const FieldState& input) {
    options.jacobiIterations = sweeps;
    options.warmStart = false;
    auto gpu = makeGpu(ctx, options);
    if (!gpu) return -1.0;
    gpu->setState(input); // its random pressure must be ignored: cold start
    runGpuStages(*gpu, kProjectAndMeasure);
    return rms(gpu->state().divergence);
}

void expectStrictlyDecreasing(const std::vector<double>& remaining, double initial) {
    ASSERT_EQ(remaining.size(), kSweepCounts.size());
    EXPECT_LT(remaining[0], initial) << "one sweep must already remove some divergence";
    for (size_t i = 1; i < remaining.size(); ++i)
        EXPECT_LT(remaining[i], remaining[i - 1])
            << kSweepCounts[i] << " sweeps leave " << remaining[i] << ", " << kSweepCounts[i - 1]
            << " sweeps left " << remaining[i - 1];
    for (size_t i = 0; i < remaining.size(); ++i)
        std::printf("  %2u sweeps: rms div %.6g (initial %.6g)\n", kSweepCounts[i], remaining[i],
                    initial);
}

void jacobiConvergesCpu(const SolverOptions& options, const FieldState& input) {
    std::vector<double> remaining;
    for (uint32_t sweeps : kSweepCounts)
        remaining.push_back(remainingDivergenceCpu(options, sweeps, input));
    expectStrictlyDecreasing(remaining, rms(initialDivergence(options, input)));
}

TEST(FluidInvariantJacobi, ResidualShrinksWithSweepsClosedBoxCpu) {
    const SolverOptions options = closedBoxOptions();
    jacobiConvergesCpu(options, randomState(options.grid, 21));
}

TEST(FluidInvariantJacobi, ResidualShrinksWithSweepsMixedBoundariesCpu) {
    const SolverOptions options = mixedBoundaryOptions();
    jacobiConvergesCpu(options, randomState(options.grid, 22));
}

using FluidInvariantJacobiGpu = GpuTest;

void jacobiConvergesGpu(const gpu::Context& ctx, const SolverOptions& options,
                        const FieldState& input) {
    std::vector<double> remaining;
    for (uint32_t sweeps : kSweepCounts)
        remaining.push_back(remainingDivergenceGpu(ctx, options, sweeps, input));
    expectStrictlyDecreasing(remaining, rms(initialDivergence(options, input)));
}

TEST_F(FluidInvariantJacobiGpu, ResidualShrinksWithSweepsClosedBox) {
    const SolverOptions options = closedBoxOptions();
    jacobiConvergesGpu(ctx(), options, randomState(options.grid, 21));
}

TEST_F(FluidInvariantJacobiGpu, ResidualShrinksWithSweepsMixedBoundaries) {
    const SolverOptions options = mixedBoundaryOptions();
    jacobiConvergesGpu(ctx(), options, randomState(options.grid, 22));
}

// =================================================================================================
// 3. Maximum principle of semi-Lagrangian pigment advection (fade 0): every new value is a
// trilinear, i.e. convex, combination of old values of the same channel, so it stays within that
// channel's [min, max].
// =================================================================================================

// Velocity scale: with h = 0.125 / 0.1 and dt = 0.04 / 0.05, |u| up to 4 gives a CFL up to ~2, so
// back-traces reach past the neighbouring cells and out of the domain (clamped or wrapped).
constexpr float kAdvectionSpeed = 4.0f;

struct ChannelRange {
    double lo[4] = {1e300, 1e300, 1e300, 1e300};
    double hi[4] = {-1e300, -1e300, -1e300, -1e300};
};

ChannelRange channelRange(const std::vector<float>& pigment) {
    ChannelRange r;
    for (size_t i = 0; i < pigment.size(); ++i) {
        const int c = int(i % 4);
        r.lo[c] = std::min(r.lo[c], double(pigment[i]));
        r.hi[c] = std::max(r.hi[c], double(pigment[i]));
    }
    return r;
}

void expectWithinRange(const std::vector<float>& input, const std::vector<float>& output,
                       double slack) {
    ASSERT_EQ(input.size(), output.size());
    const ChannelRange in = channelRange(input);
    const ChannelRange out = channelRange(output);
    for (int c = 0; c < 4; ++c) {
        EXPECT_GE(out.lo[c], in.lo[c] - slack) << "channel " << c << ": new minimum";
        EXPECT_LE(out.hi[c], in.hi[c] + slack) << "channel " << c << ": new maximum";
    }
    // Guard: the advection did move pigment (a no-op would pass trivially).
    double moved = 0.0;
    for (size_t i = 0; i < input.size(); ++i)
        moved = std::max(moved, std::abs(double(output[i]) - double(input[i])));
    EXPECT_GT(moved, 0.05) << "the advection left the pigment as it was";
}

// Random pigment with a different range per channel, none of them touching 0: a sampler that read
// 0 outside the domain, mixed channels up or extrapolated would leave the range.
FieldState advectionInput(const SolverOptions& options, uint32_t seed) {
    FieldState s = scaledVelocity(randomState(options.grid, seed), kAdvectionSpeed);
    const float lo[4] = {0.2f, 0.3f, 0.4f, 0.5f};
    for (size_t i = 0; i < s.pigment.size(); ++i)
        s.pigment[i] = lo[i % 4] + 0.4f * s.pigment[i];
    return s;
}

SolverOptions withoutFade(SolverOptions options) {
    options.fade = 0.0f;
    return options;
}

// CPU slack 0: the combination is formed in double (overshoot at most an ulp of double) and then
// rounded to float; rounding to nearest is monotonic and the bounds are floats themselves, so the
// rounded value cannot cross them.
void maximumPrincipleCpu(const SolverOptions& options, uint32_t seed) {
    const FieldState input = advectionInput(options, seed);
    fluid::ReferenceSolver cpu(options);
    cpu.setState(input);
    cpu.advectPigment();
    expectWithinRange(input.pigment, cpu.state().pigment, 0.0);
}

TEST(FluidInvariantMaximumPrinciple, PigmentAdvectionClosedBoxCpu) {
    maximumPrincipleCpu(withoutFade(closedBoxOptions()), 31);
}

TEST(FluidInvariantMaximumPrinciple, PigmentAdvectionMixedBoundariesCpu) {
    maximumPrincipleCpu(withoutFade(mixedBoundaryOptions()), 32);
}

using FluidInvariantMaximumPrincipleGpu = GpuTest;

// GPU slack 1e-6: the three nested float lerps a + t (b - a) can each overshoot max(a, b) by about
// an ulp of values < 1 (6e-8 to 1.2e-7), ~3.6e-7 in all; 1e-6 covers that and nothing more.
void maximumPrincipleGpu(const gpu::Context& ctx, const SolverOptions& options, uint32_t seed) {
    const FieldState input = advectionInput(options, seed);
    auto gpu = makeGpu(ctx, options);
    ASSERT_TRUE(gpu);
    gpu->setState(input);
    gpu->runStage(fluid::Stage::AdvectPigment);
    expectWithinRange(input.pigment, gpu->state().pigment, 1e-6);
}

TEST_F(FluidInvariantMaximumPrincipleGpu, PigmentAdvectionClosedBox) {
    maximumPrincipleGpu(ctx(), withoutFade(closedBoxOptions()), 31);
}

TEST_F(FluidInvariantMaximumPrincipleGpu, PigmentAdvectionMixedBoundaries) {
    maximumPrincipleGpu(ctx(), withoutFade(mixedBoundaryOptions()), 32);
}

} // namespace
} // namespace mfx::test
