// The fuzzers' seed corpus replayed through the fuzz targets (tests/fuzz/fuzz_targets.h): every
// committed seed, every malformed glTF of ../shared/gltf-bad, the models of ../shared/assets and
// the scenes under docs/scenes. Nothing is expected of the outcome (load or refusal) but that it
// comes back: a crash fails the test, and the suite's sanitizer pass turns a bad read, a leak or
// undefined behaviour into a failure. Each file is named on stderr before it is fed, so a crash's
// output says which.
#include "tests/fuzz/fuzz_targets.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>
#include <vector>

namespace mfx::test {
namespace {

namespace fs = std::filesystem;

// The regular files below each folder (recursively) whose extension is in `extensions`, sorted.
std::vector<fs::path> filesUnder(const std::vector<fs::path>& folders,
                                 const std::vector<std::string>& extensions) {
    std::vector<fs::path> out;
    for (const fs::path& folder : folders) {
        EXPECT_TRUE(fs::is_directory(folder)) << folder;
        if (!fs::is_directory(folder)) continue;
        for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder))
            if (entry.is_regular_file() &&
                std::find(extensions.begin(), extensions.end(),
                          entry.path().extension().string()) != extensions.end())
                out.push_back(entry.path());
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<uint8_t> bytesOf(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

size_t replay(const std::vector<fs::path>& files, void (*target)(std::span<const uint8_t>)) {
    for (const fs::path& file : files) {
        std::fprintf(stderr, "replaying %s\n", file.string().c_str());
        const std::vector<uint8_t> bytes = bytesOf(file);
        target(bytes);
    }
    return files.size();
}

const fs::path kSource = MFX_SOURCE_DIR;

TEST(FuzzCorpus, GltfSeedsReplay) {
    const size_t files = replay(filesUnder({kSource / "tests/fuzz/corpus/gltf"}, {".gltf", ".glb"}),
                                &fuzz::importGltfInput);
    EXPECT_GE(files, 8u);
}

TEST(FuzzCorpus, MalformedGltfSetReplays) {
    const size_t files =
        replay(filesUnder({kSource / "../shared/gltf-bad", kSource / "../shared/assets"},
                          {".gltf", ".glb"}),
               &fuzz::importGltfInput);
    EXPECT_GE(files, 140u); // the set has 140 files and the assets 4
}

TEST(FuzzCorpus, SceneSeedsReplay) {
    const size_t files =
        replay(filesUnder({kSource / "tests/fuzz/corpus/scene"}, {".json"}), &fuzz::readSceneInput);
    EXPECT_GE(files, 100u);
}

TEST(FuzzCorpus, DocsScenesReplay) {
    const size_t files =
        replay(filesUnder({kSource / "docs/scenes"}, {".json"}), &fuzz::readSceneInput);
    EXPECT_GE(files, 10u);
}

TEST(FuzzCorpus, PngSeedsAndTheGalleryTexturesReplay) {
    const size_t files = replay(
        filesUnder({kSource / "tests/fuzz/corpus/png", kSource / "docs/scenes/gallery/textures"},
                   {".png"}),
        &fuzz::loadTextureInput);
    EXPECT_GE(files, 10u);
}

TEST(FuzzCorpus, ScratchFolderHoldsTheBufferAndTheFileOutsideIt) {
    const fs::path& folder = fuzz::scratchFolder();
    EXPECT_TRUE(fs::is_regular_file(folder / "triangle.bin"));
    EXPECT_TRUE(fs::is_regular_file(folder.parent_path() / "outside.bin"));
}

} // namespace
} // namespace mfx::test
