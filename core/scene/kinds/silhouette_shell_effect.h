// The silhouette shell (Jones 2004): strips between the silhouettes of motion a polygon had over
// the last updates, fading out behind (render/kinds/silhouette_shell_pass.h).
#pragma once

#include "core/scene/effect_spec.h"
#include "core/scene/kinds/trail_effects.h"

namespace mfx::scene {

namespace detail {
class Object;
}

// Which edge of a polygon lies on the silhouette of motion (Sec. 3.2.4): the one between its two
// vertices facing away from their motion (the paper's figure), or between the two facing it.
enum class ShellEdgeRule { Back, Front };

// The options of a silhouette_shell effect (Sec. 3.2.2 and 3.3).
struct SilhouetteShellSpec : EffectKind<SilhouetteShellSpec> {
    static constexpr const char* kType = "silhouette_shell";
    uint32_t subdivisions = 6;     // silhouettes kept per polygon: quads in a full strip
    std::optional<float> blurTime; // seconds the shell spans; default subdivisions / fps
    float initialAlpha = 0.8f;     // alpha of each strip at the live mesh, falling to 0
    uint32_t fadeOut = 3;          // updates a polygon off the silhouette fades its strip over
    ShellEdgeRule edgeRule = ShellEdgeRule::Back;
    glm::vec4 colour{1.0f}; // the mesh's without "colour"
    bool useMeshColour = true;

    VolumeLook look; // colour over the place along it (0 at the live mesh), rim
    static std::vector<std::string> keys();
    static std::unique_ptr<EffectKindSpec> parse(const detail::Object& o);
};

} // namespace mfx::scene
