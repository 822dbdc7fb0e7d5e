// glTF 2.0 import: a .gltf (buffers embedded as base64 data URIs or in files beside it) or a .glb
// file into a Character. The file is untrusted: every index, byte range, format and number read
// from it is checked, and a file that breaks the format comes back as one Error naming the file
// and the element (e.g. "fig.gltf: skins[0].inverseBindMatrices: 3 matrices for 4 joints").
//
// What is read, and the policies where glTF leaves a choice:
//   * all nodes, reordered so that parents come first (every index remapped); a node with two
//     parents or a cycle is refused; a node matrix is decomposed into translation, rotation and
//     scale. Scenes are not consulted: every node is kept.
//   * skins: joints and inverse bind matrices (identity when absent).
//   * meshes: every triangle-list primitive (POSITION; NORMAL, computed smooth when absent;
//     TEXCOORD_0; JOINTS_0/WEIGHTS_0; indices or none; the material's base colour factor).
//     Primitives of other modes (points, lines, strips, fans) are skipped. Weights are
//     renormalised; a vertex whose weights are all zero is bound to joint 0 with weight 1.
//     Only the first set of joints and weights is read. Morph targets are ignored.
//   * a mesh is copied once per node that instances it (the copies after the first are named
//     "mesh@node"): with the node's skin, `skin` is set (the node's own transform does not apply,
//     as glTF says); without, `node` is. A mesh no node uses is kept with skin = node = -1.
//   * animations: translation, rotation and scale channels with LINEAR, STEP or CUBICSPLINE
//     samplers; morph-weight channels and channels without a target node are skipped. Clip
//     duration is the largest key time.
//   * sparse accessors are refused; images are never loaded.
//   * unnamed elements are named after their index in the file: "node_3", "mesh_0", "clip_0".
#pragma once

#include "core/anim/character.h"
#include "core/result.h"

#include <filesystem>

namespace mfx::anim {

// Loads `file` (.gltf or .glb, told apart by the file's first bytes). On success the character
// satisfies checkInvariants. Never throws; never reads outside what the file holds.
Result<Character> importGltf(const std::filesystem::path& file);

} // namespace mfx::anim
