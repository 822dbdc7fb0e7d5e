// What a trajectory is built from: the source vertices a scene names (meshes, and optionally only
// the vertices weighted to some bones), packed once for the GPU, and the palette that moves them
// at any pose. Every mesh of a character can be a source: skinned primitives read their skin's
// joints, rigid ones their node's world matrix, all through one combined palette.
#pragma once

#include "core/anim/character.h"
#include "core/anim/sampling.h"
#include "core/anim/skinning.h"
#include "core/result.h"
#include "shaders/shared/skinning.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mfx::trajectory {

struct Selection {
    std::vector<std::string> meshes; // empty: every mesh
    // Empty: every vertex of the meshes. Otherwise only the vertices whose weights to these bones
    // sum to at least minBoneWeight (a rigid primitive's vertices weigh 1 to their node).
    std::vector<std::string> bones;
    float minBoneWeight = 0.5f;
};

// One entry of the combined palette: joint `joint` of skin `skin`, or the world matrix of node
// `node` (a rigid primitive), or the identity (neither).
struct PaletteEntry {
    int skin = -1;
    int joint = -1;
    int node = -1;
};

struct Source {
    std::vector<shared::SkinVertexIn> vertices; // joints index the combined palette
    std::vector<glm::vec4> colours;             // the primitive's base colour, per vertex
    std::vector<glm::vec2> uvs;                 // per vertex; NaN where the primitive has none
    std::vector<uint32_t> triangles;            // triangles whose three vertices are selected
    std::vector<PaletteEntry> palette;
};

// The selected vertices of `character`. Unknown mesh or bone names, an out-of-range weight, or a
// selection that leaves no vertex are errors naming what is wrong and what there is.
Result<Source> selectSource(const anim::Character& character, const Selection& selection);

// The combined palette in `pose`, one dual quaternion joint per PaletteEntry, with the whole
// character placed in the world by `placement`.
std::vector<anim::DualQuatJoint> sourcePalette(const anim::Character& character,
                                               const Source& source, const anim::Pose& pose,
                                               const glm::mat4& placement = glm::mat4(1.0f));

// The two vertices of `source` that span it from the joint it hangs from outwards, for a sheet
// over the bound part (a sword's grip and tip): the one nearest to that joint and the one farthest
// from it, in the character's rest pose, that order. The joint is the palette entry carrying the
// most weight over the selection. Refused, naming why, when every vertex is as far from it.
Result<Source> twoEnds(const anim::Character& character, const Source& source);

} // namespace mfx::trajectory
