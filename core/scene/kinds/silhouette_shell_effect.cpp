#include "core/scene/kinds/silhouette_shell_effect.h"

#include "core/scene/json_object.h"

namespace mfx::scene {

// Jones 2004, Sec. 3.2.2, 3.2.4 and 3.3: the shell's settings.
std::vector<std::string> SilhouetteShellSpec::keys() {
    std::vector<std::string> keys = {"colour",        "subdivisions", "blur_time",
                                     "initial_alpha", "fade_out",     "edge_rule"};
    for (const std::string& l : volumeLookKeys())
        keys.push_back(l);
    return keys;
}

std::unique_ptr<EffectKindSpec> SilhouetteShellSpec::parse(const detail::Object& o) {
    auto s = std::make_unique<SilhouetteShellSpec>();
    s->subdivisions = o.integer("subdivisions", s->subdivisions, 1, 32);
    if (o.has("blur_time")) s->blurTime = float(o.number("blur_time", 0.2, 0.0, 60.0, true));
    s->initialAlpha = float(o.number("initial_alpha", s->initialAlpha, 0.0, 1.0));
    s->fadeOut = o.integer("fade_out", s->fadeOut, 0, 1000);
    const std::string rule = o.choice("edge_rule", "back", {"back", "front"});
    s->edgeRule = rule == "back" ? ShellEdgeRule::Back : ShellEdgeRule::Front;
    if (o.has("colour")) {
        s->colour = o.colour("colour", s->colour);
        s->useMeshColour = false;
    }
    readVolumeLook(o, s->look);
    return s;
}

} // namespace mfx::scene
