// glTF 2.0 export: a Character written as one self-contained file — a .glb (binary container,
// when the path ends in ".glb") or a .gltf with its buffer embedded as a base64 data URI. What
// importGltf (core/anim/gltf_import.h) reads back is the same character:
//   * every node, in the same order (parents come first), with its rest transform as
//     translation, rotation and scale, and its children;
//   * every skin (joints and inverse bind matrices);
//   * every mesh: POSITION (with the min/max glTF requires), NORMAL, TEXCOORD_0, JOINTS_0 (unsigned
//     byte, or unsigned short for skins of more than 256 joints), WEIGHTS_0 (float), indices
//     (unsigned short, or unsigned int past 65,535 vertices) and a material per distinct base
//     colour. A skinned mesh is placed by a new root node named after the mesh that carries the
//     mesh and its skin; a rigid mesh is carried by its node; a mesh that neither skin nor node
//     places is written but not instanced;
//   * every clip as an animation, one sampler per channel (times with their min/max; values in
//     glTF's layout, which is the Channel layout: rotations x, y, z, w; three entries per key for
//     CUBICSPLINE).
// Each accessor has its own buffer view, 4-byte aligned. Floats are written as they are, so a
// round trip is exact.
#pragma once

#include "core/anim/character.h"
#include "core/result.h"

#include <filesystem>

namespace mfx::anim {

// Writes `character` to `file`. Fails (with the reason) when the character breaks its invariants,
// when a mesh's primitives are placed differently (glTF places a whole mesh), or when the file
// cannot be written.
Status exportGltf(const Character& character, const std::filesystem::path& file);

} // namespace mfx::anim
