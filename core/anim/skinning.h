// Skinning on the CPU: dual quaternion linear blending with scale (docs/architecture.md "Formulas";
// Kavan et al. 2008, with scale split off and blended linearly) and linear blend skinning beside it
// for comparison. The GPU pass (core/anim/skin_vertices.h, shaders/core/skin_vertices.comp) is the
// twin of skinDualQuat and uses the same palette.
#pragma once

#include "core/anim/character.h"
#include "core/anim/sampling.h"
#include "core/math/dual_quat.h"

#include <vector>

namespace mfx::anim {

// One joint's matrix split for dual quaternion skinning: M = T * R * S.
struct DualQuatJoint {
    math::DualQuat rigid; // R and T
    glm::vec3 scale{1.0f};
};

std::vector<DualQuatJoint> dualQuatPalette(const std::vector<glm::mat4>& jointMatrices);

struct SkinnedVertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
};

// The transform of one vertex: the influences' dual quaternions blended by weight, each first
// aligned with the first influence of positive weight (the sign rule), normalised; their scales
// blended linearly. No positive weight gives the identity. (A per-vertex transform has a joint's
// form.) GPU twin: blendJoints in shaders/core/dual_quat.glsl.
DualQuatJoint blendJoints(const std::vector<DualQuatJoint>& palette, glm::uvec4 joints,
                          glm::vec4 weights);

// A bind-pose vertex moved by a transform: scaled (the normal by 1/S), rotated, translated.
SkinnedVertex applyTransform(const DualQuatJoint& transform, glm::vec3 position, glm::vec3 normal);

// blendJoints then applyTransform: a vertex with no positive weight stays as it is.
SkinnedVertex skinDualQuat(const std::vector<DualQuatJoint>& palette, glm::vec3 position,
                           glm::vec3 normal, glm::uvec4 joints, glm::vec4 weights);

// sum_i w_i M_i p, normals by the blended inverse transpose.
SkinnedVertex skinLinear(const std::vector<glm::mat4>& jointMatrices, glm::vec3 position,
                         glm::vec3 normal, glm::uvec4 joints, glm::vec4 weights);

enum class SkinningMethod { DualQuat, Linear };

// Every vertex of `primitive` in `pose`: skinned by its skin, or moved rigidly with its node
// (unskinned), or as stored (neither).
std::vector<SkinnedVertex> skinPrimitive(const Character& character, const Primitive& primitive,
                                         const Pose& pose,
                                         SkinningMethod method = SkinningMethod::DualQuat);

} // namespace mfx::anim
