#include "fluid/reference/reference_solver.h"

#include <cmath>

namespace mfx::fluid {

namespace {

Eigen::ArrayXd toArray(const std::vector<float>& values) {
    Eigen::ArrayXd array(Eigen::Index(values.size()));
    for (size_t i = 0; i < values.size(); ++i)
        array[Eigen::Index(i)] = double(values[i]);
    return array;
}

std::vector<float> toFloats(const Eigen::ArrayXd& array) {
    std::vector<float> values(size_t(array.size()));
    for (Eigen::Index i = 0; i < array.size(); ++i)
        values[size_t(i)] = float(array[i]);
    return values;
}

} // namespace

ReferenceSolver::ReferenceSolver(const SolverOptions& options)
    : options_(options),
      cells_(int(options.grid.cellsX), int(options.grid.cellsY), int(options.grid.cellsZ)),
      h_(double(options.grid.cellSize)) {
    setState(FieldState::zero(options.grid));
}

void ReferenceSolver::setState(const FieldState& state) {
    velocity_[0] = toArray(state.velocityX);
    velocity_[1] = toArray(state.velocityY);
    velocity_[2] = toArray(state.velocityZ);
    pressure_ = toArray(state.pressure);
    divergence_ = toArray(state.divergence);
    pigment_ = toArray(state.pigment);
    if (options_.storage == Storage::Float16) roundStoredFields();
    clearInactive();
}

FieldState ReferenceSolver::state() const {
    FieldState state;
    state.grid = options_.grid;
    state.velocityX = toFloats(velocity_[0]);
    state.velocityY = toFloats(velocity_[1]);
    state.velocityZ = toFloats(velocity_[2]);
    state.pressure = toFloats(pressure_);
    state.divergence = toFloats(divergence_);
    state.pigment = toFloats(pigment_);
    return state;
}

void ReferenceSolver::runStage(Stage stage, std::span<const shared::FluidEmitter> emitters) {
    stageEntry(stage).reference(*this, emitters);
    if (options_.storage == Storage::Float16) roundStoredFields();
    clearInactive();
}

void ReferenceSolver::step(std::span<const shared::FluidEmitter> emitters) {
    for (uint32_t substep = 0; substep < options_.substeps; ++substep) {
        for (Stage stage : stepOrder()) // markSolids first
            runStage(stage, emitters);
    }
    time_ += double(options_.dt);
}

Diagnostics computeDiagnostics(const SolverOptions& options, const FieldState& state) {
    Diagnostics d;
    const GridShape& g = state.grid;
    const double h = double(g.cellSize);
    const double volume = h * h * h;
    const std::vector<float>* faces[3] = {&state.velocityX, &state.velocityY, &state.velocityZ};

    auto countNonFinite = [&](const std::vector<float>& values) {
        for (float v : values)
            d.nonFinite += std::isfinite(v) ? 0 : 1;
    };
    for (const auto* f : faces)
        countNonFinite(*f);
    countNonFinite(state.pressure);
    countNonFinite(state.pigment);

    double maxFace = 0.0;
    for (int c = 0; c < 3; ++c) {
        const glm::uvec3 n = faceExtent(g, c);
        for (uint32_t k = 0; k < n.z; ++k)
            for (uint32_t j = 0; j < n.y; ++j)
                for (uint32_t i = 0; i < n.x; ++i) {
                    const glm::uvec3 q(i, j, k);
                    // The top face of a periodic axis duplicates face 0: count it once.
                    if (options.periodic(c) && q[c] == n[c] - 1) continue;
                    const double u = (*faces[c])[i + size_t(n.x) * (j + size_t(n.y) * k)];
                    d.kineticEnergy += 0.5 * u * u * volume;
                    maxFace = std::max(maxFace, std::abs(u));
                }
    }
    d.cfl = maxFace * double(options.substepDt()) / h;

    double sumSquares = 0.0;
    for (uint32_t k = 0; k < g.cellsZ; ++k)
        for (uint32_t j = 0; j < g.cellsY; ++j)
            for (uint32_t i = 0; i < g.cellsX; ++i) {
                glm::dvec3 centre(0.0);
                double divergence = 0.0;
                for (int c = 0; c < 3; ++c) {
                    const glm::uvec3 n = faceExtent(g, c);
                    glm::uvec3 lo(i, j, k), hi(i, j, k);
                    hi[c] += 1;
                    const double a = (*faces[c])[lo.x + size_t(n.x) * (lo.y + size_t(n.y) * lo.z)];
                    const double b = (*faces[c])[hi.x + size_t(n.x) * (hi.y + size_t(n.y) * hi.z)];
                    centre[c] = 0.5 * (a + b);
                    divergence += (b - a) / h;
                }
                d.maxDivergence = std::max(d.maxDivergence, std::abs(divergence));
                sumSquares += divergence * divergence;
                d.maxSpeed = std::max(d.maxSpeed, glm::length(centre));
                const size_t cell = g.index(i, j, k);
                for (int channel = 0; channel < 4; ++channel) {
                    const double p = state.pigment[cell * 4 + size_t(channel)];
                    d.totalPigment[channel] += p * volume;
                    d.maxPigment = std::max(d.maxPigment, p);
                }
            }
    d.rmsDivergence = std::sqrt(sumSquares / double(g.cellCount()));
    return d;
}

} // namespace mfx::fluid
