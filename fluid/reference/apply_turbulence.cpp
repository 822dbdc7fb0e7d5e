// applyTurbulence (docs/fluid.md): curl noise after Bridson, Hourihan and Nordenstam, "Curl-Noise
// for Procedural Fluid Flow" (SIGGRAPH 2007), Sec. 2: u = curl psi is divergence-free for any
// smooth potential psi. Here psi is gradient noise (Perlin, "Improving Noise", SIGGRAPH 2002: a
// lattice of pseudo-random gradients among the twelve cube-edge directions, blended with the
// quintic fade 6t^5 - 15t^4 + 10t^3), L * n(x / L) with n blended between two time layers around
// t * speed, sampled on the MAC grid's edges; its curl is taken with the grid's own differences,
// so its discrete divergence is zero up to rounding. Each face that is neither wall-normal nor
// solid gains dt * amplitude * (curl psi) of its component. Off when the amplitude is 0.
// Twin: shaders/fluid/apply_turbulence.comp with curl_noise.glsl (the same integer hash).
#include "fluid/reference/reference_solver.h"

#include <cmath>
#include <cstdint>

namespace mfx::fluid {

namespace {

// A 32-bit hash of a lattice point, a time layer and a component: each input times its own odd
// constant, combined, then MurmurHash3's finaliser. Unsigned 32-bit arithmetic, as the shader's.
uint32_t noiseHash(glm::ivec3 corner, int layer, int component) {
    uint32_t h = uint32_t(corner.x) * 0x8da6b343u ^ uint32_t(corner.y) * 0xd8163841u ^
                 uint32_t(corner.z) * 0xcb1ab31fu ^ uint32_t(layer) * 0x165667b1u ^
                 uint32_t(component) * 0x9e3779b9u;
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

glm::dvec3 noiseGradient(uint32_t h) {
    const uint32_t i = h % 12u;
    const double a = (i & 1u) ? -1.0 : 1.0, b = (i & 2u) ? -1.0 : 1.0;
    return i < 4u ? glm::dvec3(a, b, 0.0)
                  : (i < 8u ? glm::dvec3(a, 0.0, b) : glm::dvec3(0.0, a, b));
}

double noiseFade(double t) {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

double gradientNoise(glm::dvec3 p, int layer, int component) {
    const glm::dvec3 base = glm::floor(p);
    const glm::ivec3 corner(base);
    const glm::dvec3 f = p - base;
    const glm::dvec3 w(noiseFade(f.x), noiseFade(f.y), noiseFade(f.z));
    double value = 0.0;
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
                const double weight =
                    (i ? w.x : 1.0 - w.x) * (j ? w.y : 1.0 - w.y) * (k ? w.z : 1.0 - w.z);
                const glm::dvec3 g =
                    noiseGradient(noiseHash(corner + glm::ivec3(i, j, k), layer, component));
                value += weight * glm::dot(g, f - glm::dvec3(i, j, k));
            }
    return value;
}

} // namespace

void ReferenceSolver::applyTurbulence() {
    if (options_.turbulence == 0.0f) return;
    const double scale = double(options_.turbulenceScale);
    const double tau = time_ * double(options_.turbulenceSpeed);
    const double layer = std::floor(tau);
    const double blend = noiseFade(tau - layer);

    // Component c of the potential on the edge along axis c from corner e (periodic axes wrap;
    // on a wall the components tangential to it are 0 on the wall itself).
    auto edgePotential = [&](int c, glm::ivec3 e) {
        for (int a = 0; a < 3; ++a) {
            if (options_.periodic(a)) {
                e[a] = ((e[a] % cells_[a]) + cells_[a]) % cells_[a];
            } else if (a != c) {
                const auto wall = [&](int face) {
                    const Boundary kind = options_.boundaries[size_t(face)].kind;
                    return kind == Boundary::WallFreeSlip || kind == Boundary::WallNoSlip;
                };
                if ((e[a] == 0 && wall(2 * a)) || (e[a] == cells_[a] && wall(2 * a + 1)))
                    return 0.0;
            }
        }
        glm::dvec3 x = glm::dvec3(e) * h_;
        x[c] += 0.5 * h_;
        const glm::dvec3 p = x / scale;
        const double a = gradientNoise(p, int(layer), c);
        const double b = gradientNoise(p, int(layer) + 1, c);
        return scale * (a + blend * (b - a));
    };

    const double rate = dt() * double(options_.turbulence);
    for (int c = 0; c < 3; ++c) {
        const int a = (c + 1) % 3, b = (c + 2) % 3;
        glm::ivec3 da(0), db(0);
        da[a] = 1;
        db[b] = 1;
        const glm::ivec3 n = faceCount(c);
        for (int k = 0; k < n.z; ++k)
            for (int j = 0; j < n.y; ++j)
                for (int i = 0; i < n.x; ++i) {
                    const glm::ivec3 q(i, j, k);
                    if (wallNormalFace(c, q) || solidFace(c, q)) continue;
                    const double curl = ((edgePotential(b, q + da) - edgePotential(b, q)) -
                                         (edgePotential(a, q + db) - edgePotential(a, q))) /
                                        h_;
                    velocity_[size_t(c)][Eigen::Index(faceIndex(c, q))] += rate * curl;
                }
    }
}

} // namespace mfx::fluid
