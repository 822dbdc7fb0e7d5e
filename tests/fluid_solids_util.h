// Solids for the solids tests on the reference and on the GPU (test_fluid_solids.cpp,
// test_fluid_gpu_solids.cpp): spheres and capsules, the stream the still sphere stands in, the
// solid faces' error, and the flow's means over a box of fluid cells (the wake measure).
#pragma once

#include "fluid/reference/reference_solver.h"
#include "tests/fluid_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

namespace mfx::test {

inline shared::FluidSolid solidCapsule(glm::vec3 a, glm::vec3 b, float radius, glm::vec3 velocityA,
                                       glm::vec3 velocityB) {
    return {glm::vec4(a, radius), glm::vec4(b, 0.0f), glm::vec4(velocityA, 0.0f),
            glm::vec4(velocityB, 0.0f)};
}

inline shared::FluidSolid solidSphere(glm::vec3 centre, float radius,
                                      glm::vec3 velocity = glm::vec3(0.0f)) {
    return solidCapsule(centre, centre, radius, velocity, velocity);
}

// The same bits in every field of two states.
inline void expectSameBits(const fluid::FieldState& a, const fluid::FieldState& b) {
    EXPECT_EQ(a.velocityX, b.velocityX);
    EXPECT_EQ(a.velocityY, b.velocityY);
    EXPECT_EQ(a.velocityZ, b.velocityZ);
    EXPECT_EQ(a.pigment, b.pigment);
    EXPECT_EQ(a.pressure, b.pressure);
}

// A moving sphere and a moving, turning capsule inside `g`'s box.
inline std::vector<shared::FluidSolid> twoSolids(const fluid::GridShape& g) {
    const glm::vec3 size = glm::vec3(g.cellsX, g.cellsY, g.cellsZ) * g.cellSize;
    const float across = std::min(size.x, std::min(size.y, size.z));
    return {solidSphere(size * glm::vec3(0.32f, 0.41f, 0.47f), 0.23f * across, {1.2f, 0.4f, -0.3f}),
            solidCapsule(size * glm::vec3(0.61f, 0.31f, 0.33f),
                         size * glm::vec3(0.79f, 0.74f, 0.61f), 0.13f * across, {0.8f, -0.3f, 0.2f},
                         {-0.4f, 0.6f, 0.1f})};
}

// How far the nearest cell centre lies from any solid's surface, relative to its radius: the GPU
// decides inside or outside in fp32, the reference in fp64, so a comparison needs every centre
// clearly on one side (fp32 distances here are good to ~1e-7 of the unit box; 1e-5 of a radius of
// 0.1 is 1e-6).
inline double surfaceMargin(const fluid::GridShape& g, std::span<const shared::FluidSolid> solids) {
    double margin = std::numeric_limits<double>::infinity();
    for (uint32_t k = 0; k < g.cellsZ; ++k)
        for (uint32_t j = 0; j < g.cellsY; ++j)
            for (uint32_t i = 0; i < g.cellsX; ++i) {
                const glm::dvec3 x = (glm::dvec3(i, j, k) + 0.5) * double(g.cellSize);
                for (const shared::FluidSolid& s : solids) {
                    const glm::dvec3 a(s.endA), ab = glm::dvec3(s.endB) - a;
                    const double l2 = glm::dot(ab, ab);
                    const double t =
                        l2 > 0.0 ? std::clamp(glm::dot(x - a, ab) / l2, 0.0, 1.0) : 0.0;
                    const double r = s.endA.w;
                    margin = std::min(margin, std::abs(glm::length(x - (a + t * ab)) - r) / r);
                }
            }
    return margin;
}

inline constexpr fluid::GridShape kStreamGrid{32, 16, 16, 1.0f / 16.0f}; // 2 x 1 x 1 world units

// Open along x (a stream may pass), free-slip walls across it.
inline fluid::SolverOptions streamOptions() {
    fluid::SolverOptions o;
    o.grid = kStreamGrid;
    o.dt = 1.0f / 60.0f;
    o.jacobiIterations = 60;
    o.boundaries[fluid::FaceLowX].kind = fluid::Boundary::Open;
    o.boundaries[fluid::FaceHighX].kind = fluid::Boundary::Open;
    return o;
}

// The largest |u - velocity_c| over the faces `marks` (a reference with the solids set) calls
// solid, of `state`'s velocity.
inline double solidFaceError(const fluid::ReferenceSolver& marks, const fluid::FieldState& state,
                             glm::dvec3 velocity) {
    double largest = 0.0;
    marks.forEachFace([&](int c, glm::ivec3 q) {
        if (!marks.solidFace(c, q)) return;
        const double u = component(state, c)[marks.faceIndex(c, q)];
        largest = std::max(largest, std::abs(u - velocity[c]));
    });
    return largest;
}

// The velocity at the centre of cell q of `state` (each component the mean of its two faces).
inline glm::dvec3 centredVelocity(const fluid::FieldState& state,
                                  const fluid::ReferenceSolver& marks, glm::ivec3 q) {
    glm::dvec3 u;
    for (int c = 0; c < 3; ++c) {
        glm::ivec3 hi = q;
        hi[c] += 1;
        u[c] = 0.5 * (double(component(state, c)[marks.faceIndex(c, q)]) +
                      double(component(state, c)[marks.faceIndex(c, hi)]));
    }
    return u;
}

// The mean speed of the fluid cells (as `marks` has them) of the layers y in [yLow, yHigh).
inline double meanFluidSpeed(const fluid::FieldState& state, const fluid::ReferenceSolver& marks,
                             int yLow, int yHigh) {
    const fluid::GridShape& g = state.grid;
    double sum = 0.0;
    int n = 0;
    for (int k = 0; k < int(g.cellsZ); ++k)
        for (int j = yLow; j < yHigh; ++j)
            for (int i = 0; i < int(g.cellsX); ++i) {
                if (marks.solidCell({i, j, k})) continue;
                sum += glm::length(centredVelocity(state, marks, {i, j, k}));
                ++n;
            }
    return sum / std::max(n, 1);
}

// The mean x velocity and the mean magnitude of the curl of the cell-centred velocity over the
// fluid cells (as `marks` has them; the grid's outer layer left out) whose centres lie in
// [x0, x1] along x and within `half` of `centre` along y and z.
struct FlowRegion {
    double meanU = 0.0, meanCurl = 0.0;
};
inline FlowRegion flowRegion(const fluid::FieldState& state, const fluid::ReferenceSolver& marks,
                             glm::dvec3 centre, double x0, double x1, double half) {
    const fluid::GridShape& g = state.grid;
    const double h = g.cellSize;
    auto cellVelocity = [&](glm::ivec3 q) { return centredVelocity(state, marks, q); };
    FlowRegion result;
    int n = 0;
    for (int k = 1; k < int(g.cellsZ) - 1; ++k)
        for (int j = 1; j < int(g.cellsY) - 1; ++j)
            for (int i = 1; i < int(g.cellsX) - 1; ++i) {
                const glm::dvec3 x = (glm::dvec3(i, j, k) + 0.5) * h;
                if (x.x < x0 || x.x > x1 || std::abs(x.y - centre.y) > half ||
                    std::abs(x.z - centre.z) > half || marks.solidCell({i, j, k}))
                    continue;
                auto d = [&](int axis, int c) { // central difference of U_c along axis
                    glm::ivec3 a(i, j, k), b(i, j, k);
                    a[axis] -= 1;
                    b[axis] += 1;
                    return (cellVelocity(b)[c] - cellVelocity(a)[c]) / (2.0 * h);
                };
                const glm::dvec3 curl(d(1, 2) - d(2, 1), d(2, 0) - d(0, 2), d(0, 1) - d(1, 0));
                result.meanU += cellVelocity({i, j, k}).x;
                result.meanCurl += glm::length(curl);
                ++n;
            }
    if (n > 0) {
        result.meanU /= n;
        result.meanCurl /= n;
    }
    return result;
}

} // namespace mfx::test
