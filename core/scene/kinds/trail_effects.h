// The effects drawn from a trajectory queue (Xu et al., section 4): speed-lines (motion lines,
// Sec. 4.2), blur volumes (motion volumes, Sec. 4.4) and motion particles (Sec. 4.3). Each frame
// the queue gets one segment per vertex the effect binds; each kind's pass draws its live segments
// (render/kinds/speed_lines_pass.h, motion_blur_pass.h, motion_particles_pass.h).
#pragma once

#include "core/scene/effect_spec.h"

namespace mfx::scene {

namespace detail {
class Object;
}

// The trail keys every trajectory effect (and smoke) has, with `extra` keys of its own after
// them; reading them into `t` over its kind's defaults.
std::vector<std::string> trailKeys(std::initializer_list<const char*> extra = {});
void readTrail(const detail::Object& o, TrailSpec& t);

// A kind with a trail: the simulation keeps a trajectory queue for it.
template <class Kind>
struct TrailEffect : EffectKind<Kind> {
    TrailEffect() = default;
    // A trail of `shape` over every stride-th vertex in one colour.
    TrailEffect(trajectory::Kind shape, uint32_t stride, glm::vec4 colour) {
        trail.shape = shape;
        trail.stride = stride;
        trail.colour = colour;
        trail.useMeshColour = false;
    }
    TrailSpec trail;
    const TrailSpec* queue() const override { return &trail; }
    uint32_t* strideValue() override { return &trail.stride; }
};

// How a line effect's ribbons look over their life u = age / lifetime (0 at the head, where the
// line is being drawn, 1 at the tail, where it dies), as trail renderers give artists.
struct GradientStop {
    float at = 0.0f; // u
    glm::vec4 colour{1.0f};
};
struct CurveStop {
    float at = 0.0f; // u
    float value = 1.0f;
};
inline constexpr size_t kMaxRibbonStops = 8;
// How a speed-line ribbon's texture runs along it (u; v runs across it): once over the whole live
// ribbon, from the head (u = 0) to its oldest sample (u = 1); once over each frame's segment;
// `repeats` times over the trail's lifetime, by the samples' age (the pattern rides with the head
// and stretches where the motion is fast); or every `tileLength` world units along the line, by
// the distance each sample lies from where its line began (fixed on the path as it is drawn: the
// same repeats per metre at any speed).
enum class TextureUv { Stretch, PerSegment, Tiled, Distance };
// A ribbon's texture (render/kinds/speed_lines_pass.h; core/scene/ribbon_texture.h loads it). Its
// RGBA (sRGB) multiplies the ribbon's colour and alpha; its alpha is also the mask that erosion
// eats away: a texel is kept while its alpha is above the threshold at its life.
struct RibbonTexture {
    std::string file; // a PNG, relative to the scene file's folder and inside it; empty: none
    TextureUv uv = TextureUv::Stretch;
    float repeats = 4.0f;     // tiled: repeats over the lifetime
    float tileLength = 0.25f; // distance: world units a repeat covers
    float scroll = 0.0f;      // repeats a second the texture flows along the ribbon, head to tail
    // The erosion threshold (0..1) by life, 2-8 stops; empty: none.
    std::vector<CurveStop> erosionOverLife;
    float erosionSoftness = 0.1f; // the width of the threshold's soft edge, in texel alpha
};
struct RibbonLook {
    // RGBA by life, 2-8 stops, linear between them; empty: the trail's colour, faded with age.
    std::vector<GradientStop> colourOverLife;
    // The width's factor by life, 2-8 stops; empty: the built-in taper along each segment.
    std::vector<CurveStop> widthOverLife;
    float intensity = 1.0f; // HDR multiplier of the colour
    bool additive = false;  // add light instead of covering (alpha) what is behind
    float core = 0.5f;      // how far the ribbon's centre goes towards white, 0..1
    // World units in front of the scene's surfaces over which it fades out (0: a hard edge where
    // it goes behind them; depth_fade.glsl).
    float depthFade = 0.0f;
    // Camera: the ribbon turns its face to the camera. Blade: it lies in the plane of the surface
    // the line comes from, through the motion (a sword's slash plane), seen edge-on from the side.
    bool bladeFacing = false;
    // A tube, round and lit by the key light, instead of a flat strip (Xu et al., Sec. 3.2.2).
    bool tube = false;
    // Speed-lines only: one sheet spanning the bound part from the joint it hangs from outwards
    // (the bound vertices nearest to and farthest from that joint,
    // core/trajectory/trajectory_source.h twoEnds), instead of a ribbon around each bound vertex's
    // line: a sword's slash, whose outer edge is the path of its tip. The sheet reaches in from
    // its outer edge by `width` (world units, times width_over_life; at most to the inner line);
    // `facing` does not apply.
    bool sheet = false;
    RibbonTexture texture; // speed-lines only (ribbonTextureKeys)
};
// How a lit effect surface looks (motion volumes, swept volumes, afterimage smears and arcs,
// silhouette shells; shaders/render/effect_volume.*): its colour over its life, an HDR intensity,
// the blend, and a Fresnel rim light so it reads as energy. Life u is the age over the lifetime for
// motion volumes and the place along the sweep (0 at the live mesh, 1 at its far end) for the
// mesh effects.
struct VolumeLook {
    std::vector<GradientStop> colourOverLife; // RGBA by life, 2-8 stops; empty: the effect's colour
    float intensity = 1.0f;
    bool additive = false;
    float rim = 0.0f;          // the rim light's strength (HDR; 0: none)
    glm::vec3 rimColour{1.0f}; // its colour
};
std::vector<std::string> volumeLookKeys();
void readVolumeLook(const detail::Object& o, VolumeLook& v);

// The ribbon keys and their reading (speed-lines and the afterimage's speed-line variant; with
// `sheets`, "shape" may be "sheet").
std::vector<std::string> ribbonKeys();
void readRibbon(const detail::Object& o, RibbonLook& r, bool sheets = false);
// The texture keys of speed-lines (texture, texture_uv, texture_repeats, texture_tile,
// texture_scroll, erosion_over_life, erosion_softness) and their reading. The file's name is
// checked here (relative, inside the scene's folder); the file itself when the scene is loaded
// (core/scene/ribbon_texture.h).
std::vector<std::string> ribbonTextureKeys();
void readRibbonTexture(const detail::Object& o, RibbonTexture& t);
const char* textureUvName(TextureUv uv);
// The particles' share of them: colour_over_life, size_over_life (read into widthOverLife: the
// sprite's size factor), intensity, blend and depth_fade.
std::vector<std::string> particleLookKeys();
void readParticleLook(const detail::Object& o, RibbonLook& r);
// A colour ramp read as colour_over_life's stops are (2-8 objects {"at", "colour"}, "at" rising
// from 0 to 1), `span` saying what "at" places a stop on; empty where `key` is absent.
std::vector<GradientStop> readGradientStops(const detail::Object& o, const std::string& key,
                                            const char* span);
// The colour or the factor at life u.
glm::vec4 colourAt(const std::vector<GradientStop>& stops, float u);
float valueAt(const std::vector<CurveStop>& stops, float u);

struct SpeedLinesSpec : TrailEffect<SpeedLinesSpec> {
    static constexpr const char* kType = "speed_lines";
    SpeedLinesSpec() : TrailEffect(trajectory::Kind::Lines, 6, {1.0f, 0.85f, 0.3f, 1.0f}) {}
    float width = 0.012f; // ribbon width (world units)
    RibbonLook ribbon;

    static std::vector<std::string> keys() {
        std::vector<std::string> k = trailKeys({"width"});
        for (const std::vector<std::string>& keys : {ribbonKeys(), ribbonTextureKeys()})
            k.insert(k.end(), keys.begin(), keys.end());
        return k;
    }
    static std::unique_ptr<EffectKindSpec> parse(const detail::Object& o);
    StrideTarget strideTarget() const override { return StrideTarget::Lines; }
    std::vector<std::pair<const char*, float*>> lengths() override {
        // The tile's length only where there is a texture to tile (no note scales a key unused).
        if (ribbon.texture.file.empty()) return {{"width", &width}};
        return {{"width", &width}, {"texture_tile", &ribbon.texture.tileLength}};
    }
    bool fadesAgainstDepth() const override { return ribbon.depthFade > 0.0f; }
};

struct MotionBlurSpec : TrailEffect<MotionBlurSpec> {
    static constexpr const char* kType = "motion_blur";
    MotionBlurSpec() { // its stride is read but unused: volumes keep every vertex
        trail.shape = trajectory::Kind::Volumes;
        trail.lifetime = 6;
        trail.alphaStart = 0.55f;
    }
    VolumeLook look;
    static std::vector<std::string> keys() {
        std::vector<std::string> k = trailKeys();
        for (const std::string& l : volumeLookKeys())
            k.push_back(l);
        return k;
    }
    static std::unique_ptr<EffectKindSpec> parse(const detail::Object& o);
};

struct MotionParticlesSpec : TrailEffect<MotionParticlesSpec> {
    static constexpr const char* kType = "motion_particles";
    MotionParticlesSpec() : TrailEffect(trajectory::Kind::Particles, 3, {0.6f, 0.9f, 1.0f, 1.0f}) {}
    float size = 0.02f; // particle size (world units)
    RibbonLook look;    // colour and size over life, intensity, blend

    static std::vector<std::string> keys() {
        std::vector<std::string> k = trailKeys({"size"});
        for (const std::string& l : particleLookKeys())
            k.push_back(l);
        return k;
    }
    static std::unique_ptr<EffectKindSpec> parse(const detail::Object& o);
    StrideTarget strideTarget() const override { return StrideTarget::Particles; }
    std::vector<std::pair<const char*, float*>> lengths() override { return {{"size", &size}}; }
    bool fadesAgainstDepth() const override { return look.depthFade > 0.0f; }
};

} // namespace mfx::scene
