#include "fluid/scenarios.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace mfx::fluid {

namespace {

constexpr const char* kNames[] = {"puff", "jet", "swirl", "random-impulses"};

shared::FluidEmitter makeEmitter(glm::vec3 position, float radius, glm::vec3 velocity,
                                 float strength, glm::vec4 pigment) {
    return {glm::vec4(position, radius), glm::vec4(velocity, strength), pigment};
}

void setAll(std::array<FaceBoundary, 6>& faces, Boundary kind) {
    for (FaceBoundary& f : faces)
        f.kind = kind;
}

} // namespace

std::span<const char* const> scenarioNames() {
    return kNames;
}

Result<Scenario> makeScenario(std::string_view name, glm::uvec3 cells) {
    Scenario s;
    s.name = std::string(name);
    s.options.grid = {cells.x, cells.y, cells.z,
                      1.0f / float(std::max({cells.x, cells.y, cells.z}))};
    s.options.dt = 1.0f / 60.0f;
    s.options.jacobiIterations = 20;
    const GridShape& g = s.options.grid;
    const glm::vec3 size = glm::vec3(cells) * g.cellSize;
    s.initial = FieldState::zero(g);

    if (name == "puff") {
        s.description = "a buoyant puff of pigment rising in a closed box, emitted for 10 steps";
        s.options.buoyancy = 2.0f;
        s.options.fade = 0.1f;
        s.options.vorticity = 0.3f;
        s.emitters = [size](uint32_t step) {
            std::vector<shared::FluidEmitter> e;
            if (step < 10)
                e.push_back(makeEmitter(size * glm::vec3(0.5f, 0.2f, 0.5f), 0.12f * size.y,
                                        {0.0f, 1.5f, 0.0f}, 30.0f, {1.0f, 0.55f, 0.15f, 1.0f}));
            return e;
        };
    } else if (name == "jet") {
        s.description = "a continuous jet entering from -x, leaving through an open +x face";
        s.options.boundaries[FaceHighX].kind = Boundary::Open;
        s.options.fade = 0.3f;
        s.options.integrator = Integrator::RK2;
        s.emitters = [size](uint32_t) {
            return std::vector<shared::FluidEmitter>{
                makeEmitter(size * glm::vec3(0.08f, 0.5f, 0.5f), 0.1f * size.y, {2.0f, 0.0f, 0.0f},
                            40.0f, {0.2f, 0.6f, 1.0f, 1.0f})};
        };
    } else if (name == "swirl") {
        s.description = "a vortex around the z axis carrying a ring of pigment, no-slip walls";
        setAll(s.options.boundaries, Boundary::WallNoSlip);
        s.options.vorticity = 0.5f;
        s.options.viscosity = 0.001f;
        const glm::vec3 centre = 0.5f * size;
        auto swirlAt = [&](glm::vec3 x) {
            const glm::vec2 r(x.x - centre.x, x.y - centre.y);
            const float d = glm::length(r);
            const float speed =
                1.5f * d / (0.25f * size.x) * std::exp(-d * d / (0.09f * size.x * size.x));
            return d > 0.0f ? glm::vec2(-r.y, r.x) / d * speed : glm::vec2(0.0f);
        };
        for (int c = 0; c < 2; ++c) {
            const glm::uvec3 n = faceExtent(g, c);
            std::vector<float>& field = c == 0 ? s.initial.velocityX : s.initial.velocityY;
            for (uint32_t k = 0; k < n.z; ++k)
                for (uint32_t j = 0; j < n.y; ++j)
                    for (uint32_t i = 0; i < n.x; ++i) {
                        glm::vec3 x = (glm::vec3(i, j, k) + 0.5f) * g.cellSize;
                        x[c] -= 0.5f * g.cellSize;
                        // Faces on the walls stay 0.
                        const bool wall = (c == 0 && (i == 0 || i == n.x - 1)) ||
                                          (c == 1 && (j == 0 || j == n.y - 1));
                        field[i + size_t(n.x) * (j + size_t(n.y) * k)] =
                            wall ? 0.0f : swirlAt(x)[c];
                    }
        }
        for (uint32_t k = 0; k < g.cellsZ; ++k)
            for (uint32_t j = 0; j < g.cellsY; ++j)
                for (uint32_t i = 0; i < g.cellsX; ++i) {
                    const glm::vec3 x = (glm::vec3(i, j, k) + 0.5f) * g.cellSize;
                    const float d = glm::length(glm::vec2(x.x - centre.x, x.y - centre.y));
                    const float ring =
                        std::exp(-std::pow((d - 0.2f * size.x) / (0.05f * size.x), 2.0f));
                    const size_t cell = g.index(i, j, k);
                    s.initial.pigment[cell * 4 + 0] = 0.9f * ring;
                    s.initial.pigment[cell * 4 + 1] = 0.2f * ring;
                    s.initial.pigment[cell * 4 + 2] = 0.6f * ring;
                    s.initial.pigment[cell * 4 + 3] = ring;
                }
        s.emitters = [](uint32_t) { return std::vector<shared::FluidEmitter>{}; };
    } else if (name == "random-impulses") {
        s.description = "three random impulses every step, periodic in x, RK2, viscosity";
        s.options.boundaries[FaceLowX].kind = Boundary::Periodic;
        s.options.boundaries[FaceHighX].kind = Boundary::Periodic;
        s.options.integrator = Integrator::RK2;
        s.options.viscosity = 0.002f;
        s.options.vorticity = 0.2f;
        s.options.fade = 0.2f;
        s.emitters = [size](uint32_t step) {
            std::mt19937 rng(1000u + step);
            std::uniform_real_distribution<float> unit(0.0f, 1.0f), signedUnit(-1.0f, 1.0f);
            std::vector<shared::FluidEmitter> e;
            for (int i = 0; i < 3; ++i) {
                const glm::vec3 p = size * glm::vec3(unit(rng), unit(rng), unit(rng));
                const glm::vec3 v =
                    2.0f * glm::vec3(signedUnit(rng), signedUnit(rng), signedUnit(rng));
                e.push_back(makeEmitter(p, (0.05f + 0.1f * unit(rng)) * size.y, v, 25.0f,
                                        {unit(rng), unit(rng), unit(rng), 1.0f}));
            }
            return e;
        };
    } else {
        std::string known;
        for (const char* n : kNames)
            known += (known.empty() ? "" : ", ") + std::string(n);
        return Error{"no scenario \"" + std::string(name) + "\"; scenarios are: " + known};
    }
    return s;
}

} // namespace mfx::fluid
