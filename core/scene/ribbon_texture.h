// Ribbon textures (scene "texture", core/scene/kinds/trail_effects.h RibbonTexture): a PNG from
// the scene file's folder. Its name is checked as the scene is read (relative, no "..", so never
// outside the folder); the file when the scene is loaded (loadScene calls checkTextures): a regular
// file inside the folder once links are followed, at most kMaxTextureFileBytes, a PNG by its
// signature, at most kMaxTextureSide texels a side by its header before anything is decoded. The
// speed-line pass (render/kinds/speed_lines_pass.h) loads it again when it is made.
#pragma once

#include "core/result.h"
#include "core/scene/scene.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace mfx::scene {

inline constexpr uint32_t kMaxTextureSide = 4096;
inline constexpr size_t kMaxTextureFileBytes = size_t(32) << 20;

// Decoded RGBA8 texels, top row first (v = 0 at the top).
struct TextureImage {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;
};

// What is wrong with a texture's name as the scene gives it ("" when nothing; an empty name is no
// texture): too long, absolute, a ".." component, a NUL.
std::string textureNameProblem(const std::string& name);

// A PNG in memory, decoded to RGBA8 (any bit depth and channel count), refused before decoding
// when it is no PNG, its header is cut short, or a side is 0 or over kMaxTextureSide.
Result<TextureImage> decodeTexturePng(std::span<const uint8_t> bytes);

// The file a texture name of `scene` means: relative to the scene file's folder.
std::filesystem::path textureFile(const Scene& scene, const std::string& name);

// Reads and decodes texture `name` of `scene`, with the checks above; errors say what is wrong
// with the file (the caller names the key).
Result<TextureImage> loadTexture(const Scene& scene, const std::string& name);

// The texture of effect `index` (a speed-line effect with one): "<scene file>:
// effects[index].texture: <reason>" on failure.
Result<TextureImage> loadEffectTexture(const Scene& scene, size_t index);

// Loads every texture the scene's effects name (loadEffectTexture), failing on the first that
// cannot be.
Status checkTextures(const Scene& scene);

} // namespace mfx::scene
