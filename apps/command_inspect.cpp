// motionfx inspect: what the glTF importer makes of a file (meshes, joints, clips, bounds), or
// the one-line reason it refuses it.
#include "apps/commands.h"

#include "core/anim/bone_groups.h"
#include "core/anim/gltf_import.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <set>

namespace mfx::app {

namespace {

// Each node's transform in the rest pose; parents come first, so one pass suffices.
std::vector<glm::mat4> restWorldMatrices(const anim::Character& character) {
    std::vector<glm::mat4> world(character.nodes.size());
    for (size_t i = 0; i < character.nodes.size(); ++i) {
        const anim::Node& node = character.nodes[i];
        const glm::mat4 local = node.rest.matrix();
        world[i] = node.parent < 0 ? local : world[size_t(node.parent)] * local;
    }
    return world;
}

// The longest chain of joints, each the parent of the next (nodes that are not joints in between
// do not count).
int jointDepth(const anim::Character& character, const std::set<int>& joints) {
    std::vector<int> depth(character.nodes.size(), 0);
    int deepest = 0;
    for (size_t i = 0; i < character.nodes.size(); ++i) {
        const int parent = character.nodes[i].parent;
        const int above = parent < 0 ? 0 : depth[size_t(parent)];
        depth[i] = above + (joints.count(int(i)) ? 1 : 0);
        deepest = std::max(deepest, depth[i]);
    }
    return deepest;
}

void printMeshes(const anim::Character& character) {
    std::printf("meshes       %zu\n", character.meshes.size());
    for (const anim::Mesh& mesh : character.meshes) {
        size_t vertices = 0;
        size_t triangles = 0;
        for (const anim::Primitive& p : mesh.primitives) {
            vertices += p.positions.size();
            triangles += p.indices.size() / 3;
        }
        std::string placement = "not placed by any node";
        if (!mesh.primitives.empty() && mesh.primitives[0].skin >= 0)
            placement = "skinned by " + character.skins[size_t(mesh.primitives[0].skin)].name;
        else if (!mesh.primitives.empty() && mesh.primitives[0].node >= 0)
            placement = "on node " + character.nodes[size_t(mesh.primitives[0].node)].name;
        std::printf("  %s: %zu primitives, %zu vertices, %zu triangles, %s\n", mesh.name.c_str(),
                    mesh.primitives.size(), vertices, triangles, placement.c_str());
    }
}

void printJoints(const anim::Character& character) {
    std::set<int> joints;
    for (const anim::Skin& skin : character.skins)
        joints.insert(skin.joints.begin(), skin.joints.end());
    std::printf("nodes        %zu\n", character.nodes.size());
    std::printf("joints       %zu in %zu skins, hierarchy depth %d\n", joints.size(),
                character.skins.size(), jointDepth(character, joints));
}

void printClips(const anim::Character& character) {
    std::printf("clips        %zu\n", character.clips.size());
    for (const anim::Clip& clip : character.clips)
        std::printf("  %s: %.4g s, %zu channels\n", clip.name.c_str(), double(clip.duration),
                    clip.channels.size());
}

// Skinned primitives count as stored (the bind pose); rigid ones are placed by their node's rest
// transform.
void printBounds(const anim::Character& character) {
    const std::vector<glm::mat4> world = restWorldMatrices(character);
    glm::vec3 low(std::numeric_limits<float>::max());
    glm::vec3 high(std::numeric_limits<float>::lowest());
    size_t points = 0;
    for (const anim::Mesh& mesh : character.meshes)
        for (const anim::Primitive& p : mesh.primitives)
            for (const glm::vec3& position : p.positions) {
                const glm::vec3 placed =
                    p.node >= 0 ? glm::vec3(world[size_t(p.node)] * glm::vec4(position, 1.0f))
                                : position;
                low = glm::min(low, placed);
                high = glm::max(high, placed);
                ++points;
            }
    if (points == 0) {
        std::printf("bounds       none (no vertices)\n");
        return;
    }
    std::printf("bounds       (%.4g, %.4g, %.4g) to (%.4g, %.4g, %.4g)  rest pose; skinned "
                "meshes in their bind pose\n",
                double(low.x), double(low.y), double(low.z), double(high.x), double(high.y),
                double(high.z));
}

// Which bones each bone group resolves to (core/anim/bone_groups.h), as a scene's "bones" would.
void printBoneGroups(const anim::Character& character) {
    std::printf("bone groups  (what an effect's \"bones\": [\"right_leg\"] and so on select)\n");
    for (const std::string& group : anim::boneGroupNames()) {
        const std::vector<std::string> bones = anim::resolveBoneGroup(character, group);
        std::string list;
        for (const std::string& b : bones)
            list += (list.empty() ? "" : ", ") + b;
        std::printf("  %-11s %s\n", group.c_str(),
                    bones.empty() ? "(none recognised: name its bones instead)" : list.c_str());
    }
}

} // namespace

int runInspect(const cli::ParsedArgs& parsed) {
    if (parsed.positional.empty()) {
        printError("inspect needs a .gltf or .glb file (see --help)");
        return kExitUsage;
    }
    const Result<anim::Character> imported = anim::importGltf(parsed.positional[0]);
    if (!imported) {
        printError(imported.error().message);
        return kExitFailure;
    }
    const anim::Character& character = imported.value();
    std::printf("character    %s\n", character.name.c_str());
    printMeshes(character);
    printJoints(character);
    printClips(character);
    printBounds(character);
    printBoneGroups(character);
    return kExitOk;
}

} // namespace mfx::app
