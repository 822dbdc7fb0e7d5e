// The afterimage toon blur (Smith 2016, chapters 4 and 5): the rear-facing vertices of the bound
// mesh pushed back along their motion (render/kinds/afterimage_pass.h).
#pragma once

#include "core/scene/effect_spec.h"
#include "core/scene/kinds/trail_effects.h"

namespace mfx::scene {

namespace detail {
class Object;
}

// What is drawn from the pushed vertices.
enum class AfterimageVariant {
    Smear,      // the bound mesh, its rear vertices moved (single afterimage, Sec. 4.1)
    SpeedLines, // a line from each rear vertex to where it would be pushed (Sec. 4.3)
    Multi,      // arcs through the recorded history (multi-afterimage, Sec. 5.1)
};

// The options of an afterimage_smear effect (Smith 2016, Sec. 4.3 and 5.3); the defaults are the
// smear's (parse sets the other variants' colour and alpha defaults).
struct AfterimageSpec : EffectKind<AfterimageSpec> {
    static constexpr const char* kType = "afterimage_smear";
    AfterimageVariant variant = AfterimageVariant::Smear;
    float strengthCharacter = 1.0f; // f^U: push per frame of the whole character's travel
    float strengthAnimation = 2.0f; // f^V: push per frame of the animation's own motion
    float randomMin = 0.0f;         // the per-vertex random value R lies in [min, max] ...
    float randomMax = 1.0f;
    float randomThreshold = 0.0f; // ... and is 0 below this (a sharper, more jagged smear)
    float taper = 0.0f;           // push scaled by (-cos(normal, motion))^taper; 0: none
    float minSpeed = 0.0f;        // world units per second a vertex must move to smear
    float relativeSpeed = 0.0f;   // fraction of the fastest bound vertex's speed it must reach
    uint32_t afterimages = 5;     // multi: recorded positions an arc runs through
    float influencePower = 0.0f;  // multi: k of (1 - (1 - D/Dmax) j/n)^k (Sec. 5.3 b); 0: none
    // How it looks: colour (the mesh's by default), alpha from the mesh to the pushed end, and
    // for the speed-line variant every stride-th rear vertex and the line width.
    glm::vec4 colour{1.0f};
    bool useMeshColour = true;
    float alphaStart = 1.0f;
    float alphaEnd = 1.0f;
    float alphaPower = 1.0f;
    uint32_t stride = 1;
    float width = 0.008f;
    RibbonLook ribbon; // the speed-line variant's ribbon (life u from the mesh to the pushed end)
    VolumeLook look;   // the smear's and the arcs' (life u: the place along the push or the arc)

    static std::vector<std::string> keys();
    static std::unique_ptr<EffectKindSpec> parse(const detail::Object& o);
    uint32_t* strideValue() override { return &stride; }
    StrideTarget strideTarget() const override {
        return variant == AfterimageVariant::SpeedLines ? StrideTarget::Lines
                                                        : StrideTarget::EveryVertex;
    }
    std::vector<std::pair<const char*, float*>> lengths() override { return {{"width", &width}}; }
    // The speed-line variant's ribbon (the others never read it: its depth_fade is refused).
    bool fadesAgainstDepth() const override { return ribbon.depthFade > 0.0f; }
    // The smear draws the mesh itself.
    bool showsAtRest() const override { return variant == AfterimageVariant::Smear; }
};

} // namespace mfx::scene
