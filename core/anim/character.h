// A skinned, animated character as the rest of the system sees it: a node hierarchy (joints and
// the nodes above them), skins, meshes and clips. glTF 2.0 maps onto it one to one (nodes, skins,
// meshes' primitives, animations); the built-in fighter is built straight into it.
//
// Invariants every producer (importer, fighter) guarantees and every consumer may rely on:
//   * nodes[i].parent < i (parents come first), -1 for roots;
//   * every index (skin joints, channel nodes, primitive skin/node) is in range;
//   * a skin has as many inverse bind matrices as joints;
//   * a primitive's attribute arrays are all empty or of its vertex count; indices < vertex count
//     and a multiple of 3 (triangle lists); joint indices < its skin's joint count; weights >= 0
//     summing to 1 (renormalised); normals unit length;
//   * a channel's times strictly increase; values hold one entry per key (three for
//     CUBICSPLINE: in-tangent, value, out-tangent); rotations are unit quaternions.
#pragma once

#include "core/result.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mfx::anim {

// A local transform: matrix = T * R * S.
struct Transform {
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f}; // w, x, y, z
    glm::vec3 scale{1.0f};

    glm::mat4 matrix() const;
};

struct Node {
    std::string name;
    int parent = -1;
    Transform rest; // the node's own transform when no clip animates it
};

struct Skin {
    std::string name;
    std::vector<int> joints;            // node indices
    std::vector<glm::mat4> inverseBind; // one per joint
};

enum class Interpolation { Linear, Step, CubicSpline };
enum class Path { Translation, Rotation, Scale };

struct Channel {
    int node = 0;
    Path path = Path::Translation;
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times; // seconds, strictly increasing, at least one key
    // Translation/scale in xyz (w unused), rotation as a quaternion in (x, y, z, w) order.
    // CUBICSPLINE: 3 entries per key: in-tangent, value, out-tangent.
    std::vector<glm::vec4> values;
};

struct Clip {
    std::string name;
    float duration = 0.0f; // the last key time of any channel (clips start at 0)
    std::vector<Channel> channels;
};

struct Primitive {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals; // computed smooth when the file has none
    std::vector<glm::vec2> uvs;     // empty when absent
    std::vector<glm::uvec4> joints; // indices into the skin's joint list; empty when unskinned
    std::vector<glm::vec4> weights; // empty when unskinned
    std::vector<uint32_t> indices;  // triangle list
    glm::vec4 baseColor{1.0f};      // linear RGBA
    int skin = -1;                  // index into Character::skins, or -1
    // For an unskinned primitive: the node it is rigidly attached to (its world matrix places it).
    int node = -1;
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;
};

struct Character {
    std::string name;
    std::vector<Node> nodes;
    std::vector<Skin> skins;
    std::vector<Mesh> meshes;
    std::vector<Clip> clips;

    std::optional<int> findNode(std::string_view nodeName) const;
    const Mesh* findMesh(std::string_view meshName) const;
    const Clip* findClip(std::string_view clipName) const;
};

// Smooth vertex normals of a triangle list: each vertex's triangles' cross products summed (so
// larger faces weigh more), normalised; `fallback` for a vertex on no triangle of any area.
std::vector<glm::vec3> smoothNormals(const std::vector<glm::vec3>& positions,
                                     const std::vector<uint32_t>& indices, glm::vec3 fallback);

// Normals for an outline hull: each vertex gets the normalised sum of the normals of every vertex
// of the primitive at exactly its position, so vertices split at a seam or a hard edge (a
// flat-shaded mesh) move out together and the hull stays closed; `fallback` where they cancel.
std::vector<glm::vec3> weldedNormals(const std::vector<glm::vec3>& positions,
                                     const std::vector<glm::vec3>& normals, glm::vec3 fallback);

// Scales the whole character uniformly by `factor` about its origin, so that every world position
// it takes in every pose is `factor` times what it was and every rotation is unchanged: each
// node's rest translation, every translation key (CUBICSPLINE tangents too), the translation of
// every inverse bind matrix and every vertex position are multiplied by `factor`. (A node's world
// matrix W becomes D W D^-1 with D = scale(factor), so a skinned vertex W B v becomes D W B v.)
// Node scales, rotations and normals are left alone. `factor` must be finite and positive.
void scaleCharacter(Character& character, float factor);

// Checks the invariants above; the error names the element (e.g. "skins[0]: 3 inverse bind
// matrices for 4 joints"). Producers call it before handing a character out.
Status checkInvariants(const Character& character);

} // namespace mfx::anim
