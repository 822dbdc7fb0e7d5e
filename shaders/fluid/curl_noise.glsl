// Curl noise (Bridson, Hourihan, Nordenstam, "Curl-Noise for Procedural Fluid Flow", SIGGRAPH
// 2007, Sec. 2: a velocity field u = curl psi is divergence-free for any smooth potential psi).
// The potential is gradient noise sampled on the MAC grid's edges and its curl taken with the
// grid's own differences, so the discrete divergence of the result is zero up to rounding (each
// edge value enters the divergence of a cell twice with opposite signs). docs/fluid.md,
// "applyTurbulence". Used by turbulence_potential.comp, which writes the potential on every edge
// for apply_turbulence.comp to difference. Twin: fluid/reference/apply_turbulence.cpp, the same
// integer hash and the same formulas in double precision.
#ifndef MFX_CURL_NOISE_GLSL
#define MFX_CURL_NOISE_GLSL

#include "fluid_common.glsl"

// A 32-bit hash of a lattice point, a time layer and a component (the integer mix of each input
// by its own odd constant, then MurmurHash3's finaliser).
uint noiseHash(ivec3 corner, int layer, int component) {
    uint h = uint(corner.x) * 0x8da6b343u ^ uint(corner.y) * 0xd8163841u ^
             uint(corner.z) * 0xcb1ab31fu ^ uint(layer) * 0x165667b1u ^
             uint(component) * 0x9e3779b9u;
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

// One of the twelve directions to the edges of a cube (Perlin, "Improving Noise", 2002).
vec3 noiseGradient(uint h) {
    uint i = h % 12u;
    float a = (i & 1u) != 0u ? -1.0 : 1.0;
    float b = (i & 2u) != 0u ? -1.0 : 1.0;
    return i < 4u ? vec3(a, b, 0.0) : (i < 8u ? vec3(a, 0.0, b) : vec3(0.0, a, b));
}

// 6 t^5 - 15 t^4 + 10 t^3.
float noiseFade(float t) {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// Gradient noise of component `component` in time layer `layer` at p (lattice units).
float gradientNoise(vec3 p, int layer, int component) {
    vec3 base = floor(p);
    ivec3 corner = ivec3(base);
    vec3 f = p - base;
    vec3 w = vec3(noiseFade(f.x), noiseFade(f.y), noiseFade(f.z));
    float value = 0.0;
    for (int k = 0; k < 2; ++k)
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
                vec3 o = vec3(i, j, k);
                float weight = (i == 1 ? w.x : 1.0 - w.x) * (j == 1 ? w.y : 1.0 - w.y) *
                               (k == 1 ? w.z : 1.0 - w.z);
                vec3 g = noiseGradient(noiseHash(corner + ivec3(i, j, k), layer, component));
                value += weight * dot(g, f - o);
            }
    return value;
}

// Component `component` of the potential at grid position x (world units from the grid's
// corner): L * the noise at x / L, blended between the two time layers around t * speed.
// params.turbulence: x amplitude, y 1 / L, z t * speed, w L.
float noisePotential(vec3 x, int component) {
    vec3 p = x * params.turbulence.y;
    float tau = params.turbulence.z;
    float layer = floor(tau);
    float blend = noiseFade(tau - layer);
    float a = gradientNoise(p, int(layer), component);
    float b = gradientNoise(p, int(layer) + 1, component);
    return params.turbulence.w * (a + blend * (b - a));
}

// The potential's component c on the edge of that direction at edge index e: the edge runs along
// axis c from corner e, at ((e + 0.5 along c) h). On a periodic axis the index wraps; on a wall
// the potential tangential to it is 0 on the wall itself (so no flow crosses it).
float edgePotential(int c, ivec3 e) {
    ivec3 n = cellCount();
    for (int a = 0; a < 3; ++a) {
        if (periodicAxis(a)) {
            e[a] = wrapIndex(e[a], n[a]);
        } else if (a != c) {
            if ((e[a] == 0 && isWall(boundaryKind(a, false))) ||
                (e[a] == n[a] && isWall(boundaryKind(a, true))))
                return 0.0;
        }
    }
    vec3 x = vec3(e) * cellSize();
    x[c] += 0.5 * cellSize();
    return noisePotential(x, c);
}

#endif
