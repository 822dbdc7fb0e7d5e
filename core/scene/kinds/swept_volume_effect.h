// The swept volume (Wloka and Zeleznik 1996): the surface the bound mesh's silhouette edges sweep
// between recorded frames, its alpha shaped by a temporal filter
// (render/kinds/swept_volume_pass.h).
#pragma once

#include "core/scene/effect_spec.h"
#include "core/scene/kinds/trail_effects.h"

namespace mfx::scene {

namespace detail {
class Object;
}

// The temporal filter whose weight over the exposure shapes the volume's alpha (Sec. 3.4).
enum class SweptFilter { Box, Ramp, Triangle, Gaussian };

// The options of a swept_volume effect (Sec. 3.4 and 4.2).
struct SweptVolumeSpec : EffectKind<SweptVolumeSpec> {
    static constexpr const char* kType = "swept_volume";
    SweptFilter filter = SweptFilter::Ramp;
    uint32_t segments = 1;   // n: recorded frames the sweep runs back through, one a segment
    float alphaFloor = 0.1f; // the least alpha anywhere on the volume (the paper's 0.1)
    uint32_t subSamples = 4; // quads per segment
    glm::vec4 colour{1.0f};  // the mesh's without "colour"
    bool useMeshColour = true;

    VolumeLook look; // colour over the place along it (0 at the live mesh), rim
    static std::vector<std::string> keys();
    static std::unique_ptr<EffectKindSpec> parse(const detail::Object& o);
};

} // namespace mfx::scene
