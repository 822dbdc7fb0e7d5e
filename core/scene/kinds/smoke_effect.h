// The smoke effect (Xu et al., section 5): its vertices' newest trajectory segment becomes
// velocity impulses and pigment in a 3D Navier-Stokes grid each solver step (fluid/
// segment_emitters.h, fluid/smoke_solver.h); the grid is ray-marched into the frame
// (render/smoke_pass.h). Smoke effects whose grid settings are equal share one grid
// (sim/scene_simulation.h).
#pragma once

#include "core/scene/kinds/trail_effects.h"

#include <array>
#include <glm/glm.hpp>
#include <optional>

namespace mfx::scene {

enum class Emission { Vertices, Surface };

// How the smoke is shaded (render/smoke_pass.h, shaders/render/smoke_march.glsl). Presets:
// smoke: the pigment's colour, lit by the key light with self-shadowing, no light of its own;
// fire: a colour ramp by density (dark red where thin to yellow-white where dense) that glows,
//   hotter where denser; energy: a cyan-to-white ramp that glows; cartoon: a hard surface where
//   the density crosses a threshold, shaded in flat bands with an ink outline (CartoonSmoke).
enum class SmokePreset { Smoke, Fire, Energy, Cartoon };

// The cartoon look (render/smoke_pass.h, shaders/render/smoke_cartoon.glsl; after Selle, Mohr &
// Chenney, "Cartoon rendering of smoke animations", NPAR 2004, and McGuire & Fein, "Real-time
// rendering of cartoon smoke and clouds", NPAR 2006): the surface where the pigment's alpha
// crosses `threshold`, the threshold raised and lowered by `billow` of itself by noise so the
// silhouette reads as round puffs, its normal from the density's gradient, lit by the key light
// (its diffuse share times the smoke's own shadow, plus a rim towards the silhouette) and that
// light quantised into `bands` flat tones from the `colours` ramp (shadow at 0, light at 1), with
// an ink outline of `outlineWidth` pixels at the silhouette and where the surface steps in depth.
struct CartoonSmoke {
    float threshold = 0.06f; // pigment alpha where the surface lies
    uint32_t bands = 3;      // 2-4 flat tones
    // The ramp from shadow (at 0) to light (at 1); band k of n takes its colour at k / (n - 1).
    // Empty: kCartoonColours.
    std::vector<GradientStop> colours;
    float outlineWidth = 2.0f; // pixels of the output (0: none)
    glm::vec3 outlineColour{0.07f, 0.03f, 0.05f};
    float rim = 0.35f;        // light added towards the silhouette, (1 - n.v)^2 x rim
    float billow = 0.55f;     // the threshold varies by up to this share of itself
    float billowScale = 0.2f; // the puffs' size (m)
    float billowSpeed = 0.6f; // how fast the puffs' outline boils (noise periods per second)
};
// The cartoon look's default ramp: a golden light, a saturated orange, a deep red shadow (fire
// cartoon smoke, as fighting games draw their blasts), chosen to read against the default
// stage's blue-grey wall and grey floor and the fighter's red top: no blue in any of them, so
// every band stands off the blue-grey stage.
const std::vector<GradientStop>& cartoonColours();

struct SmokeShading {
    SmokePreset preset = SmokePreset::Smoke;
    float glow = 0.0f;     // emitted light (HDR) at full density; default by preset: 0, 3, 4
    uint32_t celBands = 0; // 0: smooth light; 2-4: the key light's share in that many steps
    // g of the Henyey-Greenstein phase function: > 0 scatters forwards (smoke lit from behind
    // glows), < 0 backwards, 0 evenly.
    float anisotropy = 0.3f;
    CartoonSmoke cartoon; // the cartoon preset's surface, bands and outline
};
// The preset's defaults (glow) for `preset`.
SmokeShading smokeShading(SmokePreset preset);

// What a grid is: effects with equal grid settings share it.
struct SmokeGridSpec {
    std::array<uint32_t, 3> cells{48, 48, 48};
    float cellSize = 0.05f;
    uint32_t jacobi = 20;
    float fade = 0.6f;            // pigment decay per second
    float drag = 1.0f;            // velocity decay per second
    float stepsPerSecond = 60.0f; // solver steps per second at least (whole steps per frame)
    bool follow = false;          // the grid moves with the character's root, by whole cells
    float buoyancy = 0.0f;
    float vorticity = 0.0f;
    // Curl-noise turbulence (docs/fluid.md, "applyTurbulence"): its acceleration (m/s^2, 0: off),
    // the size of its swirls (m) and how many times a second they change.
    float turbulence = 0.0f;
    float turbulenceScale = 0.25f;
    float turbulenceSpeed = 1.0f;
    // The solver's accuracy against its time (README "Accuracy against time"), named as the
    // solver's options name them (fluid/solver_options.h; a test keeps the lists the same).
    std::string pressure = "jacobi";           // jacobi, rbgs, multigrid, mgpcg
    std::string advection = "semi-lagrangian"; // semi-lagrangian, maccormack, bfecc
    std::string storage = "fp32";              // fp32, fp16 (fields stored in 16 bits)
    // dense: a box of `cells` around the effects; sparse: a virtual domain of `cells` (default
    // 256^3, multiples of 8) of which only the 8^3-cell bricks with smoke are stored and stepped
    // (fluid/sparse_smoke_solver.h), at most maxBricks of them at once.
    std::string domain = "dense";
    uint32_t maxBricks = 4096;
    float liveSpeed = 0.1f; // sparse: air faster than this (m/s) keeps a brick without smoke
    // Sparse: the world position of the domain's low corner, so its box is origin + cells x
    // cell size; absent, the domain is centred on its effects' paths, standing on the floor.
    std::optional<glm::vec3> origin;
    // The characters as moving solids the smoke flows around (docs/fluid.md, "Solids"): their body
    // capsules (core/anim/body_capsules.h), those of `collideBones` (entries as an effect's
    // "bones", of the character the effect follows; empty: every one but those of the bones the
    // grid's effects emit from, and every capsule of the other characters), each at least
    // `collideThickness` across. On by default, on either domain.
    bool collide = true;
    std::vector<std::string> collideBones;
    float collideThickness = 0.0f;
    bool sparse() const { return domain == "sparse"; }
    bool operator==(const SmokeGridSpec&) const = default;
};

// The choices of SmokeGridSpec's solver keys.
const std::vector<std::string>& smokePressureSolvers();
const std::vector<std::string>& smokeAdvectionSchemes();
const std::vector<std::string>& smokeStorages();
const std::vector<std::string>& smokeDomains();

struct SmokeSpec : TrailEffect<SmokeSpec> {
    static constexpr const char* kType = "smoke";
    // The newest segment only, as emitters.
    SmokeSpec() : TrailEffect(trajectory::Kind::Particles, 1, {0.85f, 0.35f, 0.15f, 1.0f}) {
        trail.lifetime = 2;
    }
    SmokeGridSpec grid;
    float impulseScale = 1.0f; // k
    float radius = 0.06f;      // splat radius (world units)
    float strength = 1.0f;     // pigment per second at full alpha
    Emission emission = Emission::Vertices;
    float surfaceStep = 0.02f; // UV-space step of surface emission
    uint32_t maxEmitters = 256;
    float sleepThreshold = 1e-4f; // below this pigment and speed, the solver sleeps
    SmokeShading shading;

    static std::vector<std::string> keys();
    static std::unique_ptr<EffectKindSpec> parse(const detail::Object& o);
    std::vector<std::pair<const char*, float*>> lengths() override {
        std::vector<std::pair<const char*, float*>> out = {{"cell_size", &grid.cellSize},
                                                           {"radius", &radius}};
        if (shading.preset == SmokePreset::Cartoon)
            out.emplace_back("billow_scale", &shading.cartoon.billowScale);
        return out;
    }
    // Smoke paints its pigment where its vertices are, even at rest.
    bool showsAtRest() const override { return true; }
    std::optional<float> surfaceSampling() const override {
        return emission == Emission::Surface ? std::optional<float>(surfaceStep) : std::nullopt;
    }
};

} // namespace mfx::scene
