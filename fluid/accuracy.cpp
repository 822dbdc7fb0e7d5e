#include "fluid/accuracy.h"

#include "fluid/field_compare.h"
#include "fluid/reference/reference_solver.h"

#include <cmath>
#include <numbers>

namespace mfx::fluid {

// A state on a grid twice as fine, restricted to `coarse`: pigment as the mean of the 8 fine
// cells of a coarse cell, a face velocity as the mean of the 4 fine faces on the coarse face.
FieldState restrictToCoarse(const FieldState& fine, const GridShape& coarse) {
    FieldState out = FieldState::zero(coarse);
    const GridShape& f = fine.grid;
    for (uint32_t z = 0; z < coarse.cellsZ; ++z)
        for (uint32_t y = 0; y < coarse.cellsY; ++y)
            for (uint32_t x = 0; x < coarse.cellsX; ++x)
                for (int c = 0; c < 4; ++c) {
                    double sum = 0.0;
                    for (uint32_t k = 0; k < 8; ++k)
                        sum += double(fine.pigment[f.index(2 * x + (k & 1), 2 * y + (k >> 1 & 1),
                                                           2 * z + (k >> 2 & 1)) *
                                                       4 +
                                                   size_t(c)]);
                    out.pigment[coarse.index(x, y, z) * 4 + size_t(c)] = float(sum / 8.0);
                }
    for (int c = 0; c < 3; ++c) {
        const glm::uvec3 n = faceExtent(coarse, c), nf = faceExtent(f, c);
        const std::vector<float>& src = c == 0   ? fine.velocityX
                                        : c == 1 ? fine.velocityY
                                                 : fine.velocityZ;
        std::vector<float>& dst = c == 0 ? out.velocityX : c == 1 ? out.velocityY : out.velocityZ;
        const int a = (c + 1) % 3, b = (c + 2) % 3;
        for (uint32_t z = 0; z < n.z; ++z)
            for (uint32_t y = 0; y < n.y; ++y)
                for (uint32_t x = 0; x < n.x; ++x) {
                    const glm::uvec3 q(x, y, z);
                    double sum = 0.0;
                    for (uint32_t k = 0; k < 4; ++k) {
                        glm::uvec3 p = 2u * q;
                        p[a] += k & 1;
                        p[b] += k >> 1;
                        sum += double(src[p.x + size_t(nf.x) * (p.y + size_t(nf.y) * p.z)]);
                    }
                    dst[x + size_t(n.x) * (y + size_t(n.y) * z)] = float(sum / 4.0);
                }
    }
    return out;
}

// K steps of `scenario` on the CPU reference; `exact` replaces the pressure solve by the exact
// one.
FieldState referenceRun(const Scenario& scenario, const SolverOptions& options, uint32_t steps,
                        bool exact) {
    ReferenceSolver ref(options);
    ref.setState(scenario.initial);
    for (uint32_t s = 0; s < steps; ++s) {
        const std::vector<shared::FluidEmitter> emitters = scenario.emitters(s);
        for (uint32_t sub = 0; sub < options.substeps; ++sub)
            for (Stage stage : stepOrder()) {
                if (exact && stage == Stage::SolvePressure)
                    ref.solvePressureExact();
                else
                    ref.runStage(stage, emitters);
            }
    }
    return ref.state();
}

// ||div after projection|| / ||div before|| of a state whose divergence field holds the
// divergence the last pressure solve started from.
double divergenceLeft(const SolverOptions& options, const FieldState& state) {
    ReferenceSolver ref(options);
    ref.setState(state);
    ref.computeDivergence();
    const FieldState after = ref.state();
    const std::vector<float> zero(state.divergence.size(), 0.0f);
    const double before = difference(state.divergence, zero).relL2; // ||div|| (zero's norm is 0)
    return before > 0.0 ? difference(after.divergence, zero).relL2 / before : 0.0;
}

FieldState smoothDivergentState(const SolverOptions& options) {
    FieldState s = FieldState::zero(options.grid);
    const GridShape& g = options.grid;
    const double pi = std::numbers::pi;
    for (int c = 0; c < 3; ++c) {
        const glm::uvec3 n = faceExtent(g, c);
        std::vector<float>& v = c == 0 ? s.velocityX : c == 1 ? s.velocityY : s.velocityZ;
        for (uint32_t z = 0; z < n.z; ++z)
            for (uint32_t y = 0; y < n.y; ++y)
                for (uint32_t x = 0; x < n.x; ++x) {
                    glm::dvec3 p =
                        (glm::dvec3(x, y, z) + 0.5) / glm::dvec3(g.cellsX, g.cellsY, g.cellsZ);
                    p[c] = double(glm::uvec3(x, y, z)[c]) / double(n[c] - 1);
                    v[x + size_t(n.x) * (y + size_t(n.y) * z)] =
                        float(std::sin(pi * p[c]) * std::cos(pi * p[(c + 1) % 3]) *
                              (1.0 + 0.5 * std::sin(2.0 * pi * p[(c + 2) % 3])));
                }
    }
    ReferenceSolver ref(options);
    ref.setState(s);
    ref.applyBoundaries();
    ref.computeDivergence();
    return ref.state();
}

} // namespace mfx::fluid
