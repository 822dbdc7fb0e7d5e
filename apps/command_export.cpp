// motionfx export-fighter: the built-in fighter written as a glTF 2.0 file (mesh, skin, clips),
// for looking at it in any glTF viewer or taking it into a modelling tool.
#include "apps/commands.h"

#include "core/anim/fighter.h"
#include "core/anim/gltf_export.h"

#include <cstdio>
#include <filesystem>

namespace mfx::app {

int runExportFighter(const cli::ParsedArgs& parsed) {
    if (parsed.positional.empty()) {
        printError("export-fighter needs an output file, e.g. fighter.glb (see --help)");
        return kExitUsage;
    }
    const std::filesystem::path out = parsed.positional[0];
    if (out.extension() != ".glb" && out.extension() != ".gltf") {
        printError(out.string() + ": the output file must end in .glb or .gltf");
        return kExitUsage;
    }
    const anim::Character fighter = anim::makeFighter();
    if (const Status written = anim::exportGltf(fighter, out); !written) {
        printError(written.error().message);
        return kExitFailure;
    }
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(out, ec);
    size_t joints = 0;
    for (const anim::Skin& skin : fighter.skins)
        joints += skin.joints.size();
    std::printf("wrote %s (%llu bytes): %zu meshes, %zu joints, %zu clips; `motionfx inspect %s` "
                "summarises it\n",
                out.string().c_str(), static_cast<unsigned long long>(ec ? 0 : bytes),
                fighter.meshes.size(), joints, fighter.clips.size(), out.string().c_str());
    return kExitOk;
}

} // namespace mfx::app
