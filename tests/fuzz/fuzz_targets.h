// What the fuzzers feed a hostile input to, shared by the libFuzzer harnesses (tests/fuzz/
// fuzz_*.cpp, built with clang by `./build.sh fuzz`) and by the test suite, which replays every
// file of the seed corpus through the same functions (tests/test_fuzz_corpus.cpp).
//
// Each runs the whole path a user's file takes and ignores the outcome: an input may be refused
// or accepted, but it must never crash, hang, leak, read out of bounds or hit undefined
// behaviour. The sanitizers (libFuzzer's build, the suite's second pass) report those.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>

namespace mfx::fuzz {

// A folder of its own for this process (removed at exit), holding one small buffer file
// ("triangle.bin") that a glTF input may name, with a file beside the folder ("../outside.bin")
// that it must not reach.
const std::filesystem::path& scratchFolder();

// The bytes as a .gltf/.glb file in the scratch folder, through anim::importGltf.
void importGltfInput(std::span<const uint8_t> bytes);

// The bytes as a scene file: parsed and read (scene::parseScene), its characters replaced by the
// built-in fighter (no file is read), loaded and checked (loadCast: clips, bone groups, mesh
// names), fitted (fitScene: fastest limbs, strides, hits, camera), its motionless effects found;
// and the
// same text as the viewer's editable document with each section's parameter table.
void readSceneInput(std::span<const uint8_t> bytes);

// The bytes as a ribbon texture: a file beside a scene in the scratch folder, loaded as a scene
// loads it (scene::loadTexture: its checks, then the PNG decoder).
void loadTextureInput(std::span<const uint8_t> bytes);

} // namespace mfx::fuzz
