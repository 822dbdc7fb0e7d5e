#include "tests/fuzz/fuzz_targets.h"

#include "core/anim/gltf_import.h"
#include "core/scene/ribbon_texture.h"
#include "core/scene/scene.h"
#include "core/scene/scene_document.h"
#include "core/scene/scene_fit.h"

#include <fstream>
#include <string>
#include <unistd.h>

namespace mfx::fuzz {

namespace {

void writeFile(const std::filesystem::path& path, std::span<const uint8_t> bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// The scratch folder, removed with what it holds when the process exits.
struct Scratch {
    std::filesystem::path inside;
    ~Scratch() {
        std::error_code ignored;
        std::filesystem::remove_all(inside.parent_path(), ignored);
    }
};

} // namespace

const std::filesystem::path& scratchFolder() {
    static const Scratch scratch = [] {
        const std::filesystem::path parent = std::filesystem::temp_directory_path() /
                                             ("motionfx_fuzz_" + std::to_string(long(getpid())));
        const std::filesystem::path inside = parent / "input";
        std::filesystem::create_directories(inside);
        // Three floats a vertex, one triangle: what a seed's "uri": "triangle.bin" reads.
        const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        const auto bytes =
            std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(triangle), sizeof triangle);
        writeFile(inside / "triangle.bin", bytes);
        writeFile(parent / "outside.bin", bytes);
        return Scratch{inside};
    }();
    return scratch.inside;
}

void loadTextureInput(std::span<const uint8_t> bytes) {
    writeFile(scratchFolder() / "texture.png", bytes);
    scene::Scene s;
    s.file = (scratchFolder() / "scene.json").string();
    const Result<scene::TextureImage> image = scene::loadTexture(s, "texture.png");
    if (image &&
        image.value().rgba.size() != size_t(image.value().width) * image.value().height * 4)
        __builtin_trap(); // the texels are not what the size says
}

void importGltfInput(std::span<const uint8_t> bytes) {
    const std::filesystem::path file = scratchFolder() / "input.gltf";
    writeFile(file, bytes);
    const Result<anim::Character> character = anim::importGltf(file);
    if (character) (void)anim::checkInvariants(character.value());
}

void readSceneInput(std::span<const uint8_t> bytes) {
    const std::string text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    Result<scene::Scene> parsed = scene::parseScene(text, "fuzz.json");
    if (parsed) {
        scene::Scene s = std::move(parsed).value();
        for (scene::CharacterSpec& c : s.characters)
            c.source = "fighter";
        Result<scene::Cast> cast = scene::loadCast(s);
        if (cast && scene::fitScene(s, cast.value())) // the hits too, where it has impacts
            (void)scene::motionlessEffects(s, cast.value(), scene::frameCount(s, cast.value()));
    }
    Result<scene::SceneDocument> document = scene::SceneDocument::fromText(text, "fuzz.json");
    if (!document) return;
    for (const std::string& section : scene::sceneSections())
        (void)document.value().params(section);
    for (size_t i = 0; i < document.value().scene().effects.size(); ++i)
        (void)document.value().params("effects[" + std::to_string(i) + "]");
    (void)document.value().text();
}

} // namespace mfx::fuzz
