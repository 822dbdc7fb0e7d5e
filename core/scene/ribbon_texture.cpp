#include "core/scene/ribbon_texture.h"

#include "core/scene/kinds/trail_effects.h"

#include <fstream>
#include <stb_image.h>

namespace mfx::scene {

namespace fs = std::filesystem;

std::string textureNameProblem(const std::string& name) {
    if (name.empty()) return {};
    if (name.size() > 1024) return "a file name of over 1024 characters";
    if (name.find('\0') != std::string::npos) return "the file name holds a NUL character";
    const fs::path path(name);
    if (path.is_absolute() || path.has_root_name() || path.has_root_directory())
        return "\"" + name + "\" is not relative: a texture is a file in the scene's folder";
    for (const fs::path& part : path)
        if (part == "..")
            return "\"" + name + "\" leads out of the scene's folder: a texture is a file in it";
    return {};
}

namespace {

uint32_t bigEndian32(const uint8_t* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

} // namespace

Result<TextureImage> decodeTexturePng(std::span<const uint8_t> bytes) {
    static constexpr uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() < 8 || !std::equal(kSignature, kSignature + 8, bytes.begin()))
        return Error{"not a PNG file (its first bytes are not the PNG signature)"};
    // The first chunk is the header: length 13, "IHDR", width, height (big-endian).
    if (bytes.size() < 8 + 8 + 13 || bigEndian32(&bytes[8]) != 13 ||
        std::string(reinterpret_cast<const char*>(&bytes[12]), 4) != "IHDR")
        return Error{"a PNG file without its header (cut short or damaged)"};
    const uint32_t width = bigEndian32(&bytes[16]), height = bigEndian32(&bytes[20]);
    if (width == 0 || height == 0 || width > kMaxTextureSide || height > kMaxTextureSide)
        return Error{"a PNG of " + std::to_string(width) + "x" + std::to_string(height) +
                     " texels; a texture is 1 to " + std::to_string(kMaxTextureSide) +
                     " texels a side"};
    if (bytes.size() > kMaxTextureFileBytes)
        return Error{"a PNG file of over " + std::to_string(kMaxTextureFileBytes >> 20) + " MiB"};
    int w = 0, h = 0, channels = 0;
    stbi_uc* texels = stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &channels, 4);
    if (!texels) {
        const char* reason = stbi_failure_reason();
        return Error{std::string("the PNG cannot be decoded: ") +
                     (reason ? reason : "unknown reason")};
    }
    TextureImage image;
    if (uint32_t(w) != width || uint32_t(h) != height) {
        stbi_image_free(texels);
        return Error{"the PNG decodes to another size than its header says"};
    }
    image.width = width;
    image.height = height;
    image.rgba.assign(texels, texels + size_t(width) * height * 4);
    stbi_image_free(texels);
    return image;
}

fs::path textureFile(const Scene& scene, const std::string& name) {
    fs::path folder;
    if (!scene.file.empty() && scene.file[0] != '(') folder = fs::path(scene.file).parent_path();
    return folder / name;
}

Result<TextureImage> loadTexture(const Scene& scene, const std::string& name) {
    if (const std::string problem = textureNameProblem(name); !problem.empty())
        return Error{problem};
    if (name.empty()) return Error{"no file named"};
    const fs::path file = textureFile(scene, name);
    std::error_code ec;
    if (!fs::exists(file, ec)) return Error{"no file " + file.string()};
    if (!fs::is_regular_file(file, ec)) return Error{file.string() + " is not a regular file"};
    // Inside the scene's folder once links are followed: a link may not lead out of it.
    const fs::path folder = fs::weakly_canonical(textureFile(scene, "."), ec);
    const fs::path real = ec ? fs::path() : fs::weakly_canonical(file, ec);
    if (ec) return Error{"cannot resolve " + file.string() + ": " + ec.message()};
    const fs::path inside = real.lexically_relative(folder);
    if (inside.empty() || *inside.begin() == "..")
        return Error{file.string() + " leads out of the scene's folder (to " + real.string() +
                     "): a texture is a file in it"};
    const uintmax_t size = fs::file_size(file, ec);
    if (ec) return Error{"cannot read " + file.string() + ": " + ec.message()};
    if (size > kMaxTextureFileBytes)
        return Error{file.string() + " is over " + std::to_string(kMaxTextureFileBytes >> 20) +
                     " MiB"};
    std::ifstream in(file, std::ios::binary);
    if (!in) return Error{"cannot read " + file.string()};
    // Read at most one byte past the bound (the file may have grown since).
    std::vector<uint8_t> bytes(size_t(size) + 1);
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
    bytes.resize(size_t(in.gcount()));
    Result<TextureImage> image = decodeTexturePng(bytes);
    if (!image) return Error{file.string() + ": " + image.error().message};
    return image;
}

Result<TextureImage> loadEffectTexture(const Scene& scene, size_t index) {
    const std::string where = scene.file + ": effects[" + std::to_string(index) + "].texture: ";
    if (index >= scene.effects.size()) return Error{where + "no such effect"};
    const auto* lines = scene.effects[index].as<SpeedLinesSpec>();
    if (!lines || lines->ribbon.texture.file.empty()) return Error{where + "the effect has none"};
    Result<TextureImage> image = loadTexture(scene, lines->ribbon.texture.file);
    if (!image) return Error{where + image.error().message};
    return image;
}

Status checkTextures(const Scene& scene) {
    for (size_t i = 0; i < scene.effects.size(); ++i) {
        const auto* lines = scene.effects[i].as<SpeedLinesSpec>();
        if (!lines || lines->ribbon.texture.file.empty()) continue;
        Result<TextureImage> image = loadEffectTexture(scene, i);
        if (!image) return image.error();
    }
    return Ok{};
}

} // namespace mfx::scene
