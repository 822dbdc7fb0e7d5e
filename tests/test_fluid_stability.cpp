// Stability of the smoke solver under hard settings: 2,000 whole steps on small grids,
// SmokeSolver and ReferenceSolver alike, with the
// state read back at step 1 and at kCheckpoints steps and held to bounds that follow from the
// stages (docs/fluid.md):
//
//   * no NaN or Inf in any field;
//   * pigment within [0, the most ever present or injected];
//   * kinetic energy: never growing in a closed system without a source, below a ceiling set by
//     the fastest speed present with emitters or an open face, below a wider ceiling with
//     vorticity confinement (a source by design). See EnergyBound.
//
// The hard settings: CFL 5 and 20, an impulse 1000x the usual speed, an emitter on the domain
// boundary and one wholly outside it, grids 1x1x1, 2x2x2 and 1x32x32, dt = 0, no pressure
// sweeps, vorticity confinement at 10x and viscosity at 100x their usual values; each under a
// closed box and under mixed boundaries (see Boundaries). "Emit" cases start at rest and are
// driven by emitters; "Free" cases start from a random state with no emitter. Test names read
// <case>_<Emit|Free>_<boundaries>. Non-finite emitter fields are refused at the API
// (test_fluid_stability_emitters.cpp).
#include "fluid/reference/reference_solver.h"

#include "core/enum_names.h"
#include "fluid/smoke_solver.h"
#include "tests/fluid_stability_util.h"
#include "tests/fluid_test_util.h"
#include "tests/gpu_test.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace mfx::test {
namespace {

using stability::Boundaries;
using stability::domainSize;
using stability::GpuSimulation;
using stability::kGrid;
using stability::kUsualSpeed;
using stability::kUsualViscosity;
using stability::kUsualVorticity;
using stability::Simulation;
using stability::usualEmitters;
using stability::usualOptions;

// Whole steps per run, every case, on both sides. A GPU step of these cases costs ~1.5 ms on
// lavapipe (2 threads; ~3 ms on the 1x32x32 grid), the CPU reference ~0.5-25 ms.
constexpr uint32_t kSteps = 2000;
// Checkpoints per run besides step 1: every 100 steps.
constexpr uint32_t kCheckpoints = 20;

// --- Tolerances ---------------------------------------------------------------------------------

// Energy without a source: every stage but advection provably never increases the discrete
// kinetic energy (see energyCeiling below), and the trilinear semi-Lagrangian advection dissipates
// in practice. The relative slack covers fp32 rounding of the GPU fields between two checks: each
// face value is rounded O(10) times a step with errors of either sign (2^-24 relative each), which
// moves a sum of squares by far less than 1e-4 over 100 steps.
constexpr double kEnergyRelativeSlack = 1e-4;
// Once a decaying flow reaches rounding noise it stops decaying: fp32 velocities hold ~7 digits, so
// energies below 1e-12 of the starting energy (speeds below 1e-6 of the starting speeds) are rest.
constexpr double kEnergyRestFraction = 1e-12;

// Pigment: the splat blends towards the emitter's pigment with a = 1 - exp(-x), x >= 0, and the
// advection is a convex (trilinear) combination times the fade exp(-fade dt) <= 1, so exact
// arithmetic never leaves [0, ceiling]. On the GPU, Vulkan allows exp() an error of 3 + 2|x| ulp,
// so a may come out a few ulp below 0 at an emitter's rim, overshooting by a few 2^-23 of the
// pigment per step at most; 1e-5 of the ceiling is ~80 ulp, ample for that and for lerp rounding.
constexpr double kPigmentSlack = 1e-5;

// With vorticity confinement the energy ceiling is this many times the emitter ceiling (why: see
// confinementCeiling).
constexpr double kConfinementEnergyFactor = 100.0;

// --- Cases --------------------------------------------------------------------------------------

// The boundary sets (Boundaries, tests/fluid_stability_util.h) as the test names spell them.
const char* boundariesName(Boundaries b) {
    static constexpr NamedValue<Boundaries> kNames[] = {
        {Boundaries::Closed, "Closed"},
        {Boundaries::Mixed, "Mixed"},
        {Boundaries::PeriodicNoSlip, "PeriodicNoSlip"}};
    return nameOf(b, kNames);
}

// What must hold besides the bounds.
enum class Expect {
    Bounded,     // the bounds only (source-free runs)
    Injects,     // the emitters must have put pigment into the grid by the end (not vacuous)
    NoInjection, // dt = 0: the emitters act for no time and must change nothing (but see dt0Slack)
    StaysAtRest, // an emitter wholly outside: every field stays exactly 0
};

struct StabilityCase {
    std::string name;
    fluid::SolverOptions options;
    std::vector<shared::FluidEmitter> emitters;
    bool randomStart = false;
    Expect expect = Expect::Bounded;
};

std::vector<StabilityCase> stabilityCases() {
    std::vector<StabilityCase> cases;
    for (Boundaries b : {Boundaries::Closed, Boundaries::Mixed, Boundaries::PeriodicNoSlip}) {
        const std::string suffix = std::string("_") + boundariesName(b);
        const bool all = b != Boundaries::PeriodicNoSlip;
        auto addEmit = [&](const std::string& name, const fluid::SolverOptions& o,
                           std::vector<shared::FluidEmitter> emitters, Expect expect) {
            cases.push_back({name + "_Emit" + suffix, o, std::move(emitters), false, expect});
        };
        auto addFree = [&](const std::string& name, const fluid::SolverOptions& o) {
            cases.push_back({name + "_Free" + suffix, o, {}, true, Expect::Bounded});
        };
        const float h = kGrid.cellSize;
        const fluid::SolverOptions usual = usualOptions(kGrid, b);

        // CFL N: dt = N h / (fastest speed): the emitters' fastest component, or 1 for the random
        // start (velocities in [-1, 1]).
        for (float cfl : {5.0f, 20.0f}) {
            const std::string name = "Cfl" + std::to_string(int(cfl));
            fluid::SolverOptions o = usual;
            o.dt = cfl * h / kUsualSpeed;
            if (all) addEmit(name, o, usualEmitters(kGrid, 1.0f), Expect::Injects);
            o.dt = cfl * h / 1.0f;
            addFree(name, o);
        }
        if (!all) continue;

        addEmit("Impulse1000x", usual, usualEmitters(kGrid, 1000.0f), Expect::Injects);

        {
            const glm::vec3 size = domainSize(kGrid);
            const float radius = 0.3f * size.y;
            // Centred exactly on the -x face of the domain (on a periodic axis: on the seam).
            addEmit("EmitterOnBoundary", usual,
                    {emitter({0.0f, 0.5f * size.y, 0.5f * size.z}, radius,
                             {kUsualSpeed, 1.0f, -0.5f}, 8.0f, {1.0f, 0.5f, 0.2f, 1.0f})},
                    Expect::Injects);
            // Its sphere ends a radius short of the -x face: nothing of the grid lies inside it.
            addEmit("EmitterOutside", usual,
                    {emitter({-2.0f * radius, 0.5f * size.y, 0.5f * size.z}, radius,
                             {kUsualSpeed, 1.0f, -0.5f}, 8.0f, {1.0f, 0.5f, 0.2f, 1.0f})},
                    Expect::StaysAtRest);
        }

        for (fluid::GridShape grid : {fluid::GridShape{1, 1, 1, h}, fluid::GridShape{2, 2, 2, h},
                                      fluid::GridShape{1, 32, 32, 1.0f / 32.0f}}) {
            const std::string name = "Grid" + fluid::toString(grid);
            const fluid::SolverOptions o = usualOptions(grid, b);
            addEmit(name, o, usualEmitters(grid, 1.0f), Expect::Injects);
            addFree(name, o);
        }

        {
            fluid::SolverOptions o = usual;
            o.dt = 0.0f;
            addEmit("Dt0", o, usualEmitters(kGrid, 1.0f), Expect::NoInjection);
            addFree("Dt0", o);
        }
        {
            fluid::SolverOptions o = usual;
            o.jacobiIterations = 0;
            addEmit("Jacobi0", o, usualEmitters(kGrid, 1.0f), Expect::Injects);
            addFree("Jacobi0", o);
        }
        {
            fluid::SolverOptions o = usual;
            o.vorticity = 10.0f * kUsualVorticity;
            addEmit("Vorticity10x", o, usualEmitters(kGrid, 1.0f), Expect::Injects);
            addFree("Vorticity10x", o);
        }
        {
            fluid::SolverOptions o = usual;
            o.viscosity = 100.0f * kUsualViscosity;
            // alpha = nu dt / h^2 = 0.042: each Jacobi sweep shrinks the error by 6 alpha / (1 + 6
            // alpha) = 0.2, so 8 sweeps solve the implicit diffusion to ~3e-6 (20 would cost 2.5x
            // the GPU time for nothing; the bounds hold for any count).
            o.viscosityIterations = 8;
            addEmit("Viscosity100x", o, usualEmitters(kGrid, 1.0f), Expect::Injects);
            addFree("Viscosity100x", o);
        }
    }
    return cases;
}

// --- Bounds -------------------------------------------------------------------------------------

// Faces of component c that carry energy: not wall-normal (held at 0) and not the duplicate top
// face of a periodic axis (computeDiagnostics counts it once).
uint64_t energyFaces(const fluid::SolverOptions& o, int c) {
    const glm::uvec3 n = fluid::faceExtent(o.grid, c);
    auto isWall = [](fluid::Boundary k) {
        return k == fluid::Boundary::WallFreeSlip || k == fluid::Boundary::WallNoSlip;
    };
    uint64_t along = n[c];
    if (o.periodic(c)) {
        along -= 1;
    } else {
        along -= isWall(o.boundaries[2 * c].kind) ? 1 : 0;
        along -= isWall(o.boundaries[2 * c + 1].kind) ? 1 : 0;
    }
    return along * (uint64_t(n.x) * n.y * n.z / n[c]);
}

// The emitter energy ceiling: the energy of a field with every energy-carrying face of component
// c at speed U_c, the largest |velocity_c| of any emitter or of the starting state.
//
// Why it bounds the energy. Per face and component, with still walls:
//   * splatImpulses sets u <- u + a (U - u), 0 <= a < 1: a convex blend of u and an emitter's
//     value, so |u| <= U_c is kept;
//   * advectVelocity samples trilinearly, a convex combination of faces of the same component (a
//     no-slip mirror of a still wall only flips the sign); diffuseViscosity's Jacobi sweep
//     x <- (u + alpha * sum of 6 neighbours) / (1 + 6 alpha) is a convex combination too;
//     applyBoundaries writes 0 or copies a face. All keep max |u_c| <= U_c, hence E <= ceiling.
//   * project (u -= (p_high - p_low) / h) is the one stage that can raise single faces above U_c.
//     It never raises the energy: with G the face differences of p, K = G^T G the matrix the
//     pressure sweeps solve (D its diagonal, the neighbour counts) and b = -h^2 div u = h G^T u,
//     the energy change is (h / 2) (p^T K p - 2 b^T p) = (h / 2) (|p - p*|_K^2 - |p*|_K^2), p* the
//     exact solution. Cold-started Jacobi leaves the error (I - D^-1 K)^n (0 - p*); D^-1 K has
//     eigenvalues in [0, 2] (Gershgorin: unit diagonal, off-diagonal row sums <= 1, self-neighbours
//     of 1- and 2-cell periodic axes included), so I - D^-1 K never lengthens the K-norm error:
//     the projection only removes energy, however few the sweeps.
// Semi-Lagrangian advection is not an L2 contraction, so after a projection has pushed a face
// above U_c the ceiling is no longer a theorem; it is the largest energy every other stage allows,
// reached only by a uniform flow at the top emitter speed in every component at once, which the
// projection (closed box) and the emitters' differing directions keep far away. With 0 pressure
// sweeps there is no projection and the ceiling is exact. For one emitter in a closed box it is at
// most 0.5 |v|^2 * domain volume; it is taken per component because emitters of different
// directions can each hold their own component at its maximum, and per face because an open face
// carries a layer of faces beyond the cells. Observed peaks: below 10% of it in the closed box;
// with the open face and the periodic axis the flow settles at 60-75% of it within 2,000 steps
// (Impulse1000x, Cfl20), with single faces at ~5x the fastest emitter speed.
double energyCeiling(const fluid::SolverOptions& o, const fluid::FieldState& start,
                     const std::vector<shared::FluidEmitter>& emitters) {
    const std::vector<float>* faces[3] = {&start.velocityX, &start.velocityY, &start.velocityZ};
    const double h = double(o.grid.cellSize);
    double ceiling = 0.0;
    for (int c = 0; c < 3; ++c) {
        double top = 0.0;
        for (const shared::FluidEmitter& e : emitters)
            top = std::max(top, std::abs(double(e.velocityStrength[c])));
        for (float u : *faces[c])
            top = std::max(top, std::abs(double(u)));
        ceiling += 0.5 * top * top * double(energyFaces(o, c)) * h * h * h;
    }
    return ceiling;
}

// Vorticity confinement adds dt * epsilon * h * (N x omega) to each face, |N| <= 1 and |omega| <=
// 2 sqrt(3) max|u| / h for the central differences: a force homogeneous of degree one in u, so no
// a-priori ceiling follows; what keeps the flow bounded is the dissipation of advection and
// viscosity, and the emitters pulling velocities back to their own values. Confinement is meant to
// restore swirl that the numerics dissipate, not to multiply the flow's energy: we allow
// kConfinementEnergyFactor (100) times the emitter ceiling, i.e. every face at 10x the fastest
// emitter. An instability grows speeds by up to 1 + 2 sqrt(3) epsilon dt per step (1.17 at epsilon
// = 3, dt = 1/60), so it gains the 10x in speed within ~15-25 steps: a runaway is caught long
// before it overflows, while a flow that confinement merely stirs stays far below.
double confinementCeiling(double emitterCeiling) {
    return kConfinementEnergyFactor * emitterCeiling;
}

bool hasOpenFace(const fluid::SolverOptions& o) {
    for (const fluid::FaceBoundary& face : o.boundaries)
        if (face.kind == fluid::Boundary::Open) return true;
    return false;
}

enum class EnergyBound {
    // No emitter, no confinement, no open face: a closed system (walls, periodic axes) left to
    // itself. Every stage but advection provably never adds energy (energyCeiling), and the
    // semi-Lagrangian advection only dissipates in practice: the energy must not grow between
    // checks.
    NonIncreasing,
    // Emitters, or an open face: energyCeiling. An open face is a source too: fluid flows in
    // through it at the velocity found at the boundary (zero-gradient), so energy enters from
    // outside and may grow for a while (on the CPU reference, up to ~10% per step at CFL 20 and
    // ~1% per step on a thin 1xNxN grid at CFL 1); but it comes in at speeds already present at the
    // boundary, and energyCeiling, the energy of every face at the fastest speed present, bounds
    // that spreading.
    Ceiling,
    // Vorticity confinement: confinementCeiling.
    ConfinementCeiling,
};

EnergyBound energyBound(const StabilityCase& c) {
    if (c.options.vorticity > 0.0f) return EnergyBound::ConfinementCeiling;
    if (c.emitters.empty() && !hasOpenFace(c.options)) return EnergyBound::NonIncreasing;
    return EnergyBound::Ceiling;
}

double maxEmitterPigment(const std::vector<shared::FluidEmitter>& emitters) {
    double top = 0.0;
    for (const shared::FluidEmitter& e : emitters)
        for (int channel = 0; channel < 4; ++channel)
            top = std::max(top, double(e.pigment[channel]));
    return top;
}

double minPigment(const fluid::FieldState& s) {
    double low = std::numeric_limits<double>::infinity();
    for (float p : s.pigment)
        low = std::min(low, double(p));
    return low;
}

// dt = 0 with emitters: a = 1 - exp(-0) is exactly 0 in double; Vulkan allows exp() 3 ulp, so on
// the GPU a may be up to 3 * 2^-23 per step, and after n steps a channel may have moved at most
// n * 3 * 2^-23 of the way to the emitter's value (a velocity likewise, and the energy by the
// square of that fraction of the ceiling).
double dt0Slack(uint32_t steps) {
    return double(steps) * 3.0 * std::ldexp(1.0, -23);
}

// --- Running ------------------------------------------------------------------------------------

class CpuSimulation : public Simulation {
public:
    CpuSimulation(const fluid::SolverOptions& options, std::vector<shared::FluidEmitter> emitters)
        : solver_(options), emitters_(std::move(emitters)) {}
    void setState(const fluid::FieldState& s) { solver_.setState(s); }
    void advance(uint32_t steps) override {
        for (uint32_t i = 0; i < steps; ++i)
            solver_.step(emitters_);
    }
    fluid::FieldState state() override { return solver_.state(); }

private:
    fluid::ReferenceSolver solver_;
    std::vector<shared::FluidEmitter> emitters_;
};

fluid::FieldState startState(const StabilityCase& c) {
    return c.randomStart ? randomState(c.options.grid, 20240601u)
                         : fluid::FieldState::zero(c.options.grid);
}

// Runs `steps` whole steps of `c` on `sim` (already holding the start state), checking the bounds
// at step 1 and at kCheckpoints evenly spaced steps; stops at the first checkpoint that fails.
void runAndCheck(const StabilityCase& c, uint32_t steps, Simulation& sim, const char* backend) {
    ASSERT_EQ(c.options.buoyancy, 0.0f) << "the energy bounds assume no buoyancy";
    const fluid::FieldState start = startState(c);
    const fluid::Diagnostics initial = fluid::computeDiagnostics(c.options, start);
    ASSERT_EQ(initial.nonFinite, 0u);

    const EnergyBound bound = energyBound(c);
    const double emitterCeiling = energyCeiling(c.options, start, c.emitters);
    const double ceiling = bound == EnergyBound::ConfinementCeiling
                               ? confinementCeiling(emitterCeiling)
                               : emitterCeiling;
    const double pigmentCeiling = std::max(maxEmitterPigment(c.emitters), initial.maxPigment);
    const double energyFloor = kEnergyRestFraction * initial.kineticEnergy;

    double previousEnergy = initial.kineticEnergy;
    double peakEnergy = initial.kineticEnergy;
    double peakCfl = initial.cfl;
    fluid::Diagnostics d = initial;
    const uint32_t every = std::max(1u, steps / kCheckpoints);
    uint32_t done = 0;
    while (done < steps) {
        const uint32_t next = done == 0 ? 1u : std::min(steps, (done / every + 1) * every);
        sim.advance(next - done);
        done = next;
        const fluid::FieldState s = sim.state();
        d = fluid::computeDiagnostics(c.options, s);
        const double low = minPigment(s);
        const std::string where =
            std::string(backend) + " " + c.name + ", after step " + std::to_string(done) + ": ";
        peakEnergy = std::max(peakEnergy, d.kineticEnergy);
        peakCfl = std::max(peakCfl, d.cfl);

        EXPECT_EQ(d.nonFinite, 0u) << where << "non-finite values (energy " << d.kineticEnergy
                                   << ", max pigment " << d.maxPigment << ")";
        EXPECT_GE(low, -kPigmentSlack * pigmentCeiling) << where << "negative pigment";
        EXPECT_LE(d.maxPigment, pigmentCeiling * (1.0 + kPigmentSlack))
            << where << "pigment above the most ever injected (" << pigmentCeiling << ")";
        if (bound == EnergyBound::NonIncreasing) {
            EXPECT_LE(d.kineticEnergy, previousEnergy * (1.0 + kEnergyRelativeSlack) + energyFloor)
                << where << "kinetic energy grew without a source, from " << previousEnergy
                << " at the previous check (start " << initial.kineticEnergy << ")";
        } else {
            EXPECT_LE(d.kineticEnergy, ceiling)
                << where << "kinetic energy above the ceiling "
                << (bound == EnergyBound::ConfinementCeiling
                        ? "for confinement (100x the speed ceiling)"
                        : "set by the emitter and starting speeds")
                << " (speed ceiling " << emitterCeiling << ", start " << initial.kineticEnergy
                << ", max speed " << d.maxSpeed << ")";
        }
        if (c.expect == Expect::StaysAtRest) {
            EXPECT_EQ(d.kineticEnergy, 0.0) << where << "an emitter outside the domain moved it";
            EXPECT_EQ(d.maxPigment, 0.0) << where << "an emitter outside the domain coloured it";
        }
        if (c.expect == Expect::NoInjection) {
            const double slack = dt0Slack(done);
            EXPECT_LE(d.maxPigment, slack * pigmentCeiling)
                << where << "emitters injected pigment with dt = 0";
            EXPECT_LE(d.kineticEnergy, slack * slack * emitterCeiling)
                << where << "emitters injected momentum with dt = 0";
        }
        if (::testing::Test::HasFailure()) return;
        previousEnergy = d.kineticEnergy;
    }
    if (c.expect == Expect::Injects) {
        EXPECT_GT(d.maxPigment, 0.0)
            << backend << " " << c.name << ": the emitters never reached the grid (vacuous case)";
    }
    ::testing::Test::RecordProperty("peakEnergy", std::to_string(peakEnergy));
    ::testing::Test::RecordProperty("energyCeiling", std::to_string(ceiling));
    ::testing::Test::RecordProperty("peakCfl", std::to_string(peakCfl));
}

std::string caseName(const ::testing::TestParamInfo<StabilityCase>& info) {
    return info.param.name;
}

// gtest prints the parameter of a failing test: its name, not its bytes.
void PrintTo(const StabilityCase& c, std::ostream* os) {
    *os << c.name;
}

class FluidStabilityGpuTest : public GpuTest,
                              public ::testing::WithParamInterface<StabilityCase> {};
class FluidStabilityCpuTest : public ::testing::TestWithParam<StabilityCase> {};

TEST_P(FluidStabilityGpuTest, StaysFiniteAndBounded) {
    const StabilityCase& c = GetParam();
    auto created = fluid::SmokeSolver::create(ctx(), c.options);
    ASSERT_TRUE(created.ok()) << created.error().message;
    std::unique_ptr<fluid::SmokeSolver> solver = std::move(created).value();
    solver->setState(startState(c));
    const Status set = solver->setEmitters(c.emitters);
    ASSERT_TRUE(set.ok()) << set.error().message;
    GpuSimulation sim(ctx(), std::move(solver));
    runAndCheck(c, kSteps, sim, "GPU");
}

TEST_P(FluidStabilityCpuTest, StaysFiniteAndBounded) {
    const StabilityCase& c = GetParam();
    ASSERT_TRUE(fluid::validateOptions(c.options).ok());
    ASSERT_TRUE(fluid::validateEmitters(c.emitters).ok());
    CpuSimulation sim(c.options, c.emitters);
    sim.setState(startState(c));
    runAndCheck(c, kSteps, sim, "CPU");
}

INSTANTIATE_TEST_SUITE_P(FluidStability, FluidStabilityGpuTest,
                         ::testing::ValuesIn(stabilityCases()), caseName);
INSTANTIATE_TEST_SUITE_P(FluidStability, FluidStabilityCpuTest,
                         ::testing::ValuesIn(stabilityCases()), caseName);

} // namespace
} // namespace mfx::test
