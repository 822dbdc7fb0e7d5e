#include "core/scene/kinds/smoke_effect.h"

#include "core/scene/json_object.h"

#include <cmath>

namespace mfx::scene {

using detail::Object;

std::vector<std::string> SmokeSpec::keys() {
    return trailKeys({"grid",
                      "cell_size",
                      "jacobi",
                      "fade",
                      "drag",
                      "steps_per_second",
                      "buoyancy",
                      "vorticity",
                      "impulse_k",
                      "radius",
                      "strength",
                      "emission",
                      "surface_step",
                      "max_emitters",
                      "sleep_threshold",
                      "follow",
                      "look",
                      "glow",
                      "cel_bands",
                      "anisotropy",
                      "pressure",
                      "advection",
                      "storage",
                      "domain",
                      "max_bricks",
                      "live_speed",
                      "origin",
                      "collide",
                      "collide_bones",
                      "collide_thickness",
                      "turbulence",
                      "turbulence_scale",
                      "turbulence_speed",
                      "threshold",
                      "bands",
                      "colours",
                      "outline_width",
                      "outline_colour",
                      "rim",
                      "billow",
                      "billow_scale",
                      "billow_speed"});
}

const std::vector<std::string>& smokePressureSolvers() {
    static const std::vector<std::string> names = {"jacobi", "rbgs", "multigrid", "mgpcg"};
    return names;
}

const std::vector<std::string>& smokeAdvectionSchemes() {
    static const std::vector<std::string> names = {"semi-lagrangian", "maccormack", "bfecc"};
    return names;
}

const std::vector<std::string>& smokeStorages() {
    static const std::vector<std::string> names = {"fp32", "fp16"};
    return names;
}

const std::vector<std::string>& smokeDomains() {
    static const std::vector<std::string> names = {"dense", "sparse"};
    return names;
}

SmokeShading smokeShading(SmokePreset preset) {
    SmokeShading s;
    s.preset = preset;
    s.glow = preset == SmokePreset::Fire ? 3.0f : preset == SmokePreset::Energy ? 4.0f : 0.0f;
    return s;
}

const std::vector<GradientStop>& cartoonColours() {
    static const std::vector<GradientStop> stops = {{0.0f, {0.62f, 0.07f, 0.0f, 1.0f}},
                                                    {0.5f, {1.0f, 0.42f, 0.0f, 1.0f}},
                                                    {1.0f, {1.0f, 0.87f, 0.0f, 1.0f}}};
    return stops;
}

namespace {

const char* const kCartoonKeys[] = {"threshold",    "rim",           "billow",
                                    "billow_scale", "billow_speed",  "bands",
                                    "colours",      "outline_width", "outline_colour"};
const char* const kSmoothKeys[] = {"glow", "cel_bands", "anisotropy"};

// The cartoon look's keys (SmokeShading::cartoon); refused on the other looks, as the other
// looks' light keys are refused on it.
void readCartoon(const Object& o, SmokeShading& shading) {
    if (shading.preset != SmokePreset::Cartoon) {
        for (const char* key : kCartoonKeys)
            if (o.given(key)) detail::fail(o.at(key), "only for \"look\": \"cartoon\"");
        return;
    }
    for (const char* key : kSmoothKeys)
        if (o.given(key))
            detail::fail(o.at(key), "not for \"look\": \"cartoon\" (its light is in \"bands\" "
                                    "of \"colours\", with \"rim\" and \"outline_width\")");
    CartoonSmoke& c = shading.cartoon;
    c.threshold = float(o.number("threshold", c.threshold, 0.0, 1.0, true));
    c.bands = o.integer("bands", c.bands, 2, 4);
    c.colours = readGradientStops(o, "colours", "where on the ramp (0: shadow, 1: light)");
    c.outlineWidth = float(o.number("outline_width", c.outlineWidth, 0.0, 16.0));
    c.outlineColour = glm::vec3(o.colour("outline_colour", glm::vec4(c.outlineColour, 1.0f)));
    c.rim = float(o.number("rim", c.rim, 0.0, 1.0));
    c.billow = float(o.number("billow", c.billow, 0.0, 0.9));
    c.billowScale = float(o.number("billow_scale", c.billowScale, 0.0, 10.0, true));
    c.billowSpeed = float(o.number("billow_speed", c.billowSpeed, 0.0, 100.0));
}

} // namespace

std::unique_ptr<EffectKindSpec> SmokeSpec::parse(const Object& o) {
    auto e = std::make_unique<SmokeSpec>();
    readTrail(o, e->trail);
    SmokeGridSpec& g = e->grid;
    // The solver keys the sparse domain does not have (yet: fluid/solver_options.h,
    // validateSparseOptions): given, they make the grid dense; with "domain": "sparse" they are
    // refused, and a sparse grid does not read them.
    const char* denseKey = nullptr;
    for (const char* key : {"pressure", "advection", "storage", "vorticity", "turbulence",
                            "turbulence_scale", "turbulence_speed", "follow"})
        if (!denseKey && o.given(key)) denseKey = key;
    g.domain = o.choice("domain", g.domain,
                        denseKey && !o.given("domain") ? std::vector<std::string>{"dense"}
                                                       : smokeDomains());
    const bool sparse = g.sparse();
    if (sparse && denseKey)
        detail::fail(o.at(denseKey), "only for \"domain\": \"dense\" (the sparse domain solves "
                                     "with jacobi and semi-lagrangian advection in fp32, without "
                                     "vorticity confinement or turbulence, and stands still)");
    if (sparse) g.cells = {256, 256, 256};
    if (o.has("grid")) {
        // The dense grid's cells are all stored; the sparse domain's only where there is smoke,
        // in whole bricks of 8 cells a side (a size between is rounded up).
        const std::vector<double> cells =
            o.numbers("grid", 3, 3, sparse ? 8 : 4, sparse ? 2048 : 256);
        for (size_t a = 0; a < 3; ++a) {
            if (cells[a] != std::floor(cells[a]))
                detail::fail(o.at("grid") + "[" + std::to_string(a) + "]",
                             "expected a whole number");
            g.cells[a] = sparse ? (uint32_t(cells[a]) + 7u) / 8u * 8u : uint32_t(cells[a]);
        }
    }
    g.cellSize = float(o.number("cell_size", g.cellSize, 0.0, 10.0, true));
    g.jacobi = o.integer("jacobi", g.jacobi, 0, 10000);
    if (!sparse) {
        g.pressure = o.choice("pressure", g.pressure, smokePressureSolvers());
        g.advection = o.choice("advection", g.advection, smokeAdvectionSchemes());
        g.storage = o.choice("storage", g.storage, smokeStorages());
    }
    g.fade = float(o.number("fade", g.fade, 0.0, 100.0));
    g.drag = float(o.number("drag", g.drag, 0.0, 100.0));
    g.stepsPerSecond = float(o.number("steps_per_second", g.stepsPerSecond, 1.0, 1000.0));
    if (!sparse) g.follow = o.boolean("follow", g.follow);
    // Solids, on either domain and with every pressure solver of the dense grid, on unless
    // "collide": false. The bones and thickness are read beside "collide" and used when it is
    // true.
    g.collide = o.boolean("collide", g.collide);
    g.collideBones = o.strings("collide_bones");
    g.collideThickness = float(o.number("collide_thickness", g.collideThickness, 0.0, 10.0));
    g.buoyancy = float(o.number("buoyancy", g.buoyancy, -100.0, 100.0));
    if (!sparse) {
        g.vorticity = float(o.number("vorticity", g.vorticity, 0.0, 100.0));
        g.turbulence = float(o.number("turbulence", g.turbulence, 0.0, 1000.0));
        g.turbulenceScale =
            float(o.number("turbulence_scale", g.turbulenceScale, 0.0, 100.0, true));
        g.turbulenceSpeed = float(o.number("turbulence_speed", g.turbulenceSpeed, 0.0, 100.0));
    }
    if (sparse) {
        g.maxBricks = o.integer("max_bricks", g.maxBricks, 1, 1u << 20);
        g.liveSpeed = float(o.number("live_speed", g.liveSpeed, 0.0, 1000.0));
        if (o.has("origin")) g.origin = o.vec3("origin", glm::vec3(0.0f), -1e4, 1e4);
    } else {
        for (const char* key : {"max_bricks", "live_speed", "origin"})
            if (o.given(key)) detail::fail(o.at(key), "only for \"domain\": \"sparse\"");
    }
    e->impulseScale = float(o.number("impulse_k", e->impulseScale, 0.0, 100.0));
    e->radius = float(o.number("radius", e->radius, 0.0, 10.0, true));
    e->strength = float(o.number("strength", e->strength, 0.0, 1000.0));
    e->emission = o.choice("emission", "vertices", {"vertices", "surface"}) == "surface"
                      ? Emission::Surface
                      : Emission::Vertices;
    e->surfaceStep = float(o.number("surface_step", e->surfaceStep, 0.0, 1.0, true));
    e->maxEmitters = o.integer("max_emitters", e->maxEmitters, 1, 4096);
    e->sleepThreshold = float(o.number("sleep_threshold", e->sleepThreshold, 0.0, 1.0, true));
    const std::string look = o.choice("look", "smoke", {"smoke", "fire", "energy", "cartoon"});
    e->shading = smokeShading(look == "fire"      ? SmokePreset::Fire
                              : look == "energy"  ? SmokePreset::Energy
                              : look == "cartoon" ? SmokePreset::Cartoon
                                                  : SmokePreset::Smoke);
    if (e->shading.preset != SmokePreset::Cartoon) {
        e->shading.glow = float(o.number("glow", e->shading.glow, 0.0, 1000.0));
        if (o.has("cel_bands")) e->shading.celBands = o.integer("cel_bands", 0, 2, 4);
        e->shading.anisotropy = float(o.number("anisotropy", e->shading.anisotropy, -0.9, 0.9));
    }
    readCartoon(o, e->shading);
    return e;
}

} // namespace mfx::scene
