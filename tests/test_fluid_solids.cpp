// Moving solids in the smoke (docs/fluid.md, "Solids"), on the CPU reference: a still sphere in a
// uniform stream lets nothing through its faces and the exact pressure leaves the air as
// divergence-free as without it; a sphere moving through still air carries its faces, pushes the
// air ahead aside and leaves a wake; pigment never enters a solid; no solids is the solver as
// before; bad solids are refused in one line.
#include "core/anim/fighter.h"
#include "fluid/body_solids.h"
#include "fluid/reference/reference_solver.h"
#include "tests/fluid_solids_util.h"
#include "tests/kick_band_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace mfx::test {
namespace {

using fluid::ReferenceSolver;

constexpr fluid::GridShape kGrid = kStreamGrid;

shared::FluidSolid sphere(glm::vec3 centre, float radius, glm::vec3 velocity = glm::vec3(0.0f)) {
    return solidSphere(centre, radius, velocity);
}

// The largest |divergence| over the fluid cells of the solver's current velocity.
double fluidDivergence(ReferenceSolver& s) {
    s.computeDivergence();
    const fluid::FieldState state = s.state();
    double largest = 0.0;
    for (int k = 0; k < int(kGrid.cellsZ); ++k)
        for (int j = 0; j < int(kGrid.cellsY); ++j)
            for (int i = 0; i < int(kGrid.cellsX); ++i)
                if (!s.solidCell({i, j, k}))
                    largest =
                        std::max(largest, std::abs(double(state.divergence[kGrid.index(i, j, k)])));
    return largest;
}

// The largest |u_solid - u| over the solid faces (each component's against `velocity`).
double solidFaceError(const ReferenceSolver& s, glm::dvec3 velocity) {
    return test::solidFaceError(s, s.state(), velocity);
}

TEST(FluidSolids, AStillSphereInAUniformStreamLetsNothingThroughAndLeavesNoDivergence) {
    const SolverOptions options = streamOptions();
    fluid::FieldState stream = fluid::FieldState::zero(kGrid);
    for (float& u : stream.velocityX)
        u = 1.0f;
    ReferenceSolver with(options), without(options);
    with.setState(stream);
    without.setState(stream);
    const shared::FluidSolid ball = sphere({1.0f, 0.5f, 0.5f}, 0.2f);
    with.setSolids(std::span(&ball, 1));
    ASSERT_TRUE(with.hasSolids());
    // The exact pressure of the sphere's divergence, then the projection, as a step ends.
    for (ReferenceSolver* s : {&with, &without}) {
        s->computeDivergence();
        s->solvePressureExact();
        s->project();
    }
    EXPECT_EQ(solidFaceError(with, glm::dvec3(0.0)), 0.0) << "flux through the solid's faces";
    const double withDiv = fluidDivergence(with), withoutDiv = fluidDivergence(without);
    std::printf("largest |div| over the fluid cells: %.2e with the sphere, %.2e without\n", withDiv,
                withoutDiv);
    EXPECT_LE(withDiv, 1e-9); // the stream's own scale: 1 / h = 16 per second
    EXPECT_LE(withoutDiv, 1e-9);
    // The stream goes round: faster beside the sphere than far from it.
    const fluid::FieldState state = with.state();
    const double beside = state.velocityX[with.faceIndex(0, {16, 8, 3})];
    EXPECT_GT(beside, 1.05) << "the air beside the sphere speeds up";

    // A whole step (advection, Jacobi sweeps) keeps the faces shut and the divergence down.
    with.setState(stream);
    with.step({});
    EXPECT_EQ(solidFaceError(with, glm::dvec3(0.0)), 0.0);
    EXPECT_LT(with.pressureResidual(), 0.5);
}

TEST(FluidSolids, AMovingSphereCarriesItsFacesPushesTheAirAsideAndLeavesAWake) {
    SolverOptions options = streamOptions();
    options.jacobiIterations = 80;
    options.integrator = fluid::Integrator::RK2;
    ReferenceSolver s(options);
    s.setState(fluid::FieldState::zero(kGrid));
    const glm::vec3 velocity(2.0f, 0.0f, 0.0f);
    const float radius = 0.15f;
    glm::vec3 centre(0.4f, 0.5f, 0.5f);
    for (int step = 0; step < 24; ++step) {
        centre += velocity * options.dt;
        const shared::FluidSolid ball = sphere(centre, radius, velocity);
        s.setSolids(std::span(&ball, 1));
        s.step({});
        ASSERT_EQ(solidFaceError(s, glm::dvec3(velocity)), 0.0) << "step " << step;
    }
    const fluid::FieldState state = s.state();
    const double h = kGrid.cellSize, r = radius;
    const glm::dvec3 at(centre);
    const FlowRegion ahead = flowRegion(state, s, at, at.x + r, at.x + r + 4 * h, r);
    const FlowRegion behind = flowRegion(state, s, at, at.x - r - 6 * h, at.x - r, r);
    std::printf("ahead of the sphere: mean u_x %.3f m/s, mean |curl| %.2f /s; behind: %.3f, "
                "%.2f\n",
                ahead.meanU, ahead.meanCurl, behind.meanU, behind.meanCurl);
    EXPECT_GT(ahead.meanU, 0.2 * double(velocity.x)) << "the air ahead is pushed";
    EXPECT_GT(behind.meanCurl, ahead.meanCurl) << "a wake behind";
}

TEST(FluidSolids, PigmentNeverEntersASolid) {
    SolverOptions options = streamOptions();
    options.fade = 0.0f;
    ReferenceSolver s(options);
    fluid::FieldState cloud = fluid::FieldState::zero(kGrid);
    for (size_t cell = 0; cell < cloud.pigment.size() / 4; ++cell)
        for (int channel = 0; channel < 4; ++channel)
            cloud.pigment[cell * 4 + size_t(channel)] = 0.8f;
    s.setState(cloud);
    glm::vec3 centre(0.3f, 0.5f, 0.5f);
    const glm::vec3 velocity(3.0f, 0.5f, 0.0f);
    for (int step = 0; step < 12; ++step) {
        centre += velocity * options.dt;
        const shared::FluidSolid ball = sphere(centre, 0.18f, velocity);
        s.setSolids(std::span(&ball, 1));
        s.step({});
        const fluid::FieldState state = s.state();
        double inside = 0.0, largest = 0.0;
        for (int k = 0; k < int(kGrid.cellsZ); ++k)
            for (int j = 0; j < int(kGrid.cellsY); ++j)
                for (int i = 0; i < int(kGrid.cellsX); ++i)
                    for (int channel = 0; channel < 4; ++channel) {
                        const double p = state.pigment[kGrid.index(i, j, k) * 4 + size_t(channel)];
                        largest = std::max(largest, p);
                        if (s.solidCell({i, j, k})) inside += std::abs(p);
                    }
        EXPECT_EQ(inside, 0.0) << "step " << step;
        EXPECT_LE(largest, 0.8 + 1e-6) << "no pigment made, step " << step;
    }
}

TEST(FluidSolids, NoSolidsIsTheSolverAsBefore) {
    const SolverOptions options = mixedBoundaryOptions();
    const fluid::FieldState input = randomState(options.grid, 5);
    const auto emitters = twoEmitters(options.grid);
    ReferenceSolver plain(options), empty(options);
    plain.setState(input);
    empty.setState(input);
    empty.setSolids({});
    EXPECT_FALSE(empty.hasSolids());
    for (int step = 0; step < 3; ++step) {
        plain.step(emitters);
        empty.step(emitters);
    }
    expectSameBits(plain.state(), empty.state());
}

TEST(FluidSolids, ASolidTouchingTheDomainsEdgeKeepsTheWall) {
    SolverOptions options = closedBoxOptions();
    ReferenceSolver s(options);
    s.setState(randomState(options.grid, 9));
    // Centred on the -x wall, moving into it and along it.
    const shared::FluidSolid ball = sphere({0.0f, 0.7f, 0.4f}, 0.3f, {-1.0f, 0.5f, 0.0f});
    s.setSolids(std::span(&ball, 1));
    for (int step = 0; step < 5; ++step)
        s.step({});
    const fluid::FieldState state = s.state();
    for (int k = 0; k < int(options.grid.cellsZ); ++k)
        for (int j = 0; j < int(options.grid.cellsY); ++j)
            EXPECT_EQ(state.velocityX[s.faceIndex(0, {0, j, k})], 0.0f) << "the wall stays shut";
    EXPECT_EQ(fluid::computeDiagnostics(options, state).nonFinite, 0u);
    EXPECT_EQ(solidFaceError(s, glm::dvec3(-1.0, 0.5, 0.0)), 0.0);
}

// The fighter's roundhouse kick through a band of smoke, its body as capsules (bodySolids of
// fitBodyCapsules), on a 32³ grid of 6.25 cm round it: in every step no pigment is inside the
// body's solid cells, and the air of the cloud moves (pushed by the leg; without the body, and
// with no emitter, it stays still).
TEST(FluidSolids, TheKickThroughACloudPushesItAndNeverHoldsPigmentInside) {
    const SolverOptions options = kickBandOptions();
    ReferenceSolver with(options), without(options);
    with.setState(kickBandCloud(options.grid));
    without.setState(kickBandCloud(options.grid));
    const KickBandRun run = runKickThroughBand(
        options,
        [&](const std::vector<shared::FluidSolid>& solids) {
            with.setSolids(solids);
            with.step({});
            without.step({});
        },
        [&] { return with.state(); }, [&] { return without.state(); });
    std::printf("%d steps: pigment inside the body at most %.3g of the total; the band's mean "
                "speed %.3f m/s with the body, %.3f without\n",
                run.steps, run.largestInside, run.speed, run.stillSpeed);
    EXPECT_LE(run.largestInside, 0.01);
    EXPECT_GT(run.speed, 0.05);
    EXPECT_EQ(run.stillSpeed, 0.0);
}

TEST(FluidSolids, BadSolidsAreRefusedNamingTheSolid) {
    ReferenceSolver s(streamOptions());
    auto refused = [&](const std::vector<shared::FluidSolid>& solids) {
        try {
            s.setSolids(solids);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    shared::FluidSolid bad = sphere({1, 0.5f, 0.5f}, 0.1f);
    bad.endB.y = std::nanf("");
    EXPECT_EQ(refused({sphere({1, 0.5f, 0.5f}, 0.1f), bad}),
              "solid 1: an end or the radius is not finite");
    EXPECT_EQ(refused({sphere({1, 0.5f, 0.5f}, 0.0f)}), "solid 0: radius must be > 0");
    shared::FluidSolid fast = sphere({1, 0.5f, 0.5f}, 0.1f);
    fast.velocityB.x = INFINITY;
    EXPECT_EQ(refused({fast}), "solid 0: a velocity is not finite");
    SolverOptions oneLevel = streamOptions();
    oneLevel.pressureSolver = fluid::PressureSolver::Multigrid;
    oneLevel.multigrid.levels = 1; // a multigrid's coarse levels are needed (they see no solids)
    ReferenceSolver m(oneLevel);
    const shared::FluidSolid ball = sphere({1, 0.5f, 0.5f}, 0.1f);
    EXPECT_THROW(m.setSolids(std::span(&ball, 1)), std::invalid_argument);
}

} // namespace
} // namespace mfx::test
