#include "core/trajectory/trajectory_source.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace mfx::trajectory {

namespace {

std::string listNames(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names)
        out += (out.empty() ? "" : ", ") + name;
    return out.empty() ? "(none)" : out;
}

} // namespace

Result<Source> selectSource(const anim::Character& character, const Selection& selection) {
    if (!(selection.minBoneWeight > 0.0f && selection.minBoneWeight <= 1.0f))
        return Error{"minBoneWeight " + std::to_string(selection.minBoneWeight) +
                     " is outside (0, 1]"};
    std::vector<std::string> meshNames;
    for (const anim::Mesh& mesh : character.meshes)
        meshNames.push_back(mesh.name);
    std::set<size_t> meshes;
    for (size_t i = 0; i < selection.meshes.size(); ++i) {
        const auto it = std::find(meshNames.begin(), meshNames.end(), selection.meshes[i]);
        if (it == meshNames.end())
            return Error{"meshes[" + std::to_string(i) + "]: no mesh \"" + selection.meshes[i] +
                         "\"; meshes are: " + listNames(meshNames)};
        meshes.insert(size_t(it - meshNames.begin()));
    }
    if (selection.meshes.empty())
        for (size_t m = 0; m < character.meshes.size(); ++m)
            meshes.insert(m);

    std::set<int> bones;
    for (size_t i = 0; i < selection.bones.size(); ++i) {
        const std::optional<int> node = character.findNode(selection.bones[i]);
        if (!node) {
            std::vector<std::string> nodeNames;
            for (const anim::Node& n : character.nodes)
                nodeNames.push_back(n.name);
            return Error{"bones[" + std::to_string(i) + "]: no bone \"" + selection.bones[i] +
                         "\"; bones are: " + listNames(nodeNames)};
        }
        bones.insert(*node);
    }

    Source source;
    std::map<std::pair<int, int>, uint32_t> paletteIndex; // (skin, joint) or (-1, node)
    auto entryFor = [&](int skin, int jointOrNode) {
        const auto key = std::make_pair(skin, jointOrNode);
        auto it = paletteIndex.find(key);
        if (it != paletteIndex.end()) return it->second;
        PaletteEntry entry;
        if (skin >= 0) {
            entry.skin = skin;
            entry.joint = jointOrNode;
        } else {
            entry.node = jointOrNode;
        }
        source.palette.push_back(entry);
        return paletteIndex.emplace(key, uint32_t(source.palette.size() - 1)).first->second;
    };

    for (size_t m : meshes)
        for (const anim::Primitive& p : character.meshes[m].primitives) {
            std::vector<int64_t> remap(p.positions.size(), -1);
            for (size_t v = 0; v < p.positions.size(); ++v) {
                shared::SkinVertexIn in{};
                in.position = glm::vec4(p.positions[v], 1.0f);
                in.normal = glm::vec4(p.normals[v], 0.0f);
                float boneWeight = 0.0f;
                if (p.skin >= 0) {
                    const anim::Skin& skin = character.skins[size_t(p.skin)];
                    for (int k = 0; k < 4; ++k) {
                        const uint32_t joint = p.joints[v][k];
                        const float w = p.weights[v][k];
                        in.joints[k] = entryFor(p.skin, int(joint));
                        in.weights[k] = w;
                        if (w > 0.0f && bones.count(skin.joints[joint])) boneWeight += w;
                    }
                } else {
                    in.joints = glm::uvec4(entryFor(-1, p.node));
                    in.weights = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
                    boneWeight = bones.count(p.node) ? 1.0f : 0.0f;
                }
                if (!bones.empty() && boneWeight < selection.minBoneWeight) continue;
                remap[v] = int64_t(source.vertices.size());
                source.vertices.push_back(in);
                source.colours.push_back(p.baseColor);
                source.uvs.push_back(p.uvs.empty() ? glm::vec2(std::nanf("")) : p.uvs[v]);
            }
            for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
                const int64_t a = remap[p.indices[t]], b = remap[p.indices[t + 1]],
                              c = remap[p.indices[t + 2]];
                if (a < 0 || b < 0 || c < 0) continue;
                source.triangles.insert(source.triangles.end(),
                                        {uint32_t(a), uint32_t(b), uint32_t(c)});
            }
        }
    if (source.vertices.empty())
        return Error{"the selection (meshes: " + listNames(selection.meshes) +
                     "; bones: " + listNames(selection.bones) + ") holds no vertex"};
    return source;
}

std::vector<anim::DualQuatJoint> sourcePalette(const anim::Character& character,
                                               const Source& source, const anim::Pose& pose,
                                               const glm::mat4& placement) {
    std::map<int, std::vector<glm::mat4>> skinMatrices;
    std::vector<glm::mat4> matrices;
    matrices.reserve(source.palette.size());
    for (const PaletteEntry& entry : source.palette) {
        glm::mat4 m(1.0f);
        if (entry.skin >= 0) {
            auto it = skinMatrices.find(entry.skin);
            if (it == skinMatrices.end())
                it = skinMatrices
                         .emplace(entry.skin, anim::jointMatrices(character, entry.skin, pose))
                         .first;
            m = it->second[size_t(entry.joint)];
        } else if (entry.node >= 0) {
            m = pose.world[size_t(entry.node)];
        }
        matrices.push_back(placement * m);
    }
    return anim::dualQuatPalette(matrices);
}

Result<Source> twoEnds(const anim::Character& character, const Source& source) {
    if (source.vertices.empty())
        return Error{"a sheet needs bound vertices; the selection has none"};
    const anim::Pose rest = anim::samplePose(character, nullptr, 0.0f);
    // The joint the part hangs from: the palette entry with the most weight over the selection.
    std::vector<double> weight(source.palette.size(), 0.0);
    for (const shared::SkinVertexIn& v : source.vertices)
        for (int k = 0; k < 4; ++k)
            if (v.joints[k] < weight.size()) weight[v.joints[k]] += double(v.weights[k]);
    const size_t heaviest = size_t(std::max_element(weight.begin(), weight.end()) - weight.begin());
    glm::vec3 pivot(0.0f);
    if (heaviest < source.palette.size()) {
        const PaletteEntry& entry = source.palette[heaviest];
        int node = entry.node;
        if (entry.skin >= 0 && entry.joint >= 0)
            node = character.skins[size_t(entry.skin)].joints[size_t(entry.joint)];
        if (node >= 0 && size_t(node) < rest.world.size())
            pivot = glm::vec3(rest.world[size_t(node)][3]);
    }
    const std::vector<anim::DualQuatJoint> palette = sourcePalette(character, source, rest);
    size_t nearest = 0, farthest = 0;
    float near = std::numeric_limits<float>::max(), far = -1.0f;
    for (size_t i = 0; i < source.vertices.size(); ++i) {
        const shared::SkinVertexIn& v = source.vertices[i];
        const glm::vec3 p = anim::skinDualQuat(palette, glm::vec3(v.position), glm::vec3(v.normal),
                                               v.joints, v.weights)
                                .position;
        const float d = glm::distance(p, pivot);
        if (d < near) near = d, nearest = i;
        if (d > far) far = d, farthest = i;
    }
    if (!(far - near > 1e-6f))
        return Error{"a sheet needs bound vertices at different distances from the joint they "
                     "hang from; the " +
                     std::to_string(source.vertices.size()) + " selected are all " +
                     std::to_string(near) + " from it"};
    Source out;
    out.palette = source.palette;
    for (const size_t i : {nearest, farthest}) {
        out.vertices.push_back(source.vertices[i]);
        out.colours.push_back(source.colours[i]);
        if (i < source.uvs.size()) out.uvs.push_back(source.uvs[i]);
    }
    return out;
}

} // namespace mfx::trajectory
