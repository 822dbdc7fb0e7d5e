#include "core/anim/character.h"

#include <array>
#include <cmath>
#include <map>

namespace mfx::anim {

glm::mat4 Transform::matrix() const {
    glm::mat4 m = glm::mat4_cast(rotation);
    m[0] *= scale.x;
    m[1] *= scale.y;
    m[2] *= scale.z;
    m[3] = glm::vec4(translation, 1.0f);
    return m;
}

std::optional<int> Character::findNode(std::string_view nodeName) const {
    for (size_t i = 0; i < nodes.size(); ++i)
        if (nodes[i].name == nodeName) return int(i);
    return std::nullopt;
}

const Mesh* Character::findMesh(std::string_view meshName) const {
    for (const Mesh& mesh : meshes)
        if (mesh.name == meshName) return &mesh;
    return nullptr;
}

const Clip* Character::findClip(std::string_view clipName) const {
    for (const Clip& clip : clips)
        if (clip.name == clipName) return &clip;
    return nullptr;
}

std::vector<glm::vec3> smoothNormals(const std::vector<glm::vec3>& positions,
                                     const std::vector<uint32_t>& indices, glm::vec3 fallback) {
    std::vector<glm::vec3> normals(positions.size(), glm::vec3(0.0f));
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        const uint32_t a = indices[i], b = indices[i + 1], c = indices[i + 2];
        const glm::vec3 n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
        normals[a] += n;
        normals[b] += n;
        normals[c] += n;
    }
    for (glm::vec3& n : normals) {
        const float length = glm::length(n);
        n = length > 0.0f && std::isfinite(length) ? n / length : fallback;
    }
    return normals;
}

std::vector<glm::vec3> weldedNormals(const std::vector<glm::vec3>& positions,
                                     const std::vector<glm::vec3>& normals, glm::vec3 fallback) {
    std::map<std::array<float, 3>, glm::vec3> sums;
    for (size_t v = 0; v < positions.size() && v < normals.size(); ++v)
        sums[{positions[v].x, positions[v].y, positions[v].z}] += normals[v];
    std::vector<glm::vec3> welded(positions.size(), fallback);
    for (size_t v = 0; v < positions.size(); ++v) {
        const auto sum = sums.find({positions[v].x, positions[v].y, positions[v].z});
        if (sum == sums.end()) continue; // a position without a normal: the fallback
        const float length = glm::length(sum->second);
        if (length > 1e-6f && std::isfinite(length)) welded[v] = sum->second / length;
    }
    return welded;
}

namespace {

bool finite(const glm::vec4& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}
bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

} // namespace

Status checkInvariants(const Character& c) {
    const int nodeCount = int(c.nodes.size());
    for (int i = 0; i < nodeCount; ++i) {
        const Node& n = c.nodes[i];
        const std::string where = "nodes[" + std::to_string(i) + "]";
        if (n.parent < -1 || n.parent >= i)
            return Error{where + ": parent " + std::to_string(n.parent) +
                         " does not come before the node"};
        if (!finite(n.rest.translation) || !finite(n.rest.scale) ||
            !finite(glm::vec4(n.rest.rotation.x, n.rest.rotation.y, n.rest.rotation.z,
                              n.rest.rotation.w)))
            return Error{where + ": transform is not finite"};
    }
    for (size_t s = 0; s < c.skins.size(); ++s) {
        const Skin& skin = c.skins[s];
        const std::string where = "skins[" + std::to_string(s) + "]";
        if (skin.joints.empty()) return Error{where + ": no joints"};
        if (skin.inverseBind.size() != skin.joints.size())
            return Error{where + ": " + std::to_string(skin.inverseBind.size()) +
                         " inverse bind matrices for " + std::to_string(skin.joints.size()) +
                         " joints"};
        for (size_t j = 0; j < skin.joints.size(); ++j)
            if (skin.joints[j] < 0 || skin.joints[j] >= nodeCount)
                return Error{where + ".joints[" + std::to_string(j) + "]: node " +
                             std::to_string(skin.joints[j]) + " does not exist"};
    }
    for (size_t m = 0; m < c.meshes.size(); ++m) {
        for (size_t p = 0; p < c.meshes[m].primitives.size(); ++p) {
            const Primitive& prim = c.meshes[m].primitives[p];
            const std::string where =
                "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "]";
            const size_t count = prim.positions.size();
            auto sized = [&](size_t n) { return n == 0 || n == count; };
            if (prim.normals.size() != count) return Error{where + ": normal count differs"};
            if (!sized(prim.uvs.size())) return Error{where + ": texture coordinate count differs"};
            if (prim.joints.size() != prim.weights.size() || !sized(prim.joints.size()))
                return Error{where + ": joint or weight count differs"};
            if (prim.indices.size() % 3 != 0)
                return Error{where + ": index count is not a multiple of 3"};
            for (uint32_t index : prim.indices)
                if (index >= count)
                    return Error{where + ": index " + std::to_string(index) + " >= vertex count " +
                                 std::to_string(count)};
            if (prim.skin >= int(c.skins.size()) || prim.skin < -1)
                return Error{where + ": skin " + std::to_string(prim.skin) + " does not exist"};
            if (prim.node >= nodeCount || prim.node < -1)
                return Error{where + ": node " + std::to_string(prim.node) + " does not exist"};
            if (prim.skin >= 0) {
                if (prim.joints.empty()) return Error{where + ": skinned but has no joints"};
                const size_t joints = c.skins[size_t(prim.skin)].joints.size();
                for (size_t v = 0; v < prim.joints.size(); ++v)
                    for (int k = 0; k < 4; ++k)
                        if (prim.weights[v][k] > 0.0f && prim.joints[v][k] >= joints)
                            return Error{where + ": vertex " + std::to_string(v) + " joint " +
                                         std::to_string(prim.joints[v][k]) + " >= joint count " +
                                         std::to_string(joints)};
            }
            for (size_t v = 0; v < count; ++v)
                if (!finite(prim.positions[v]) || !finite(prim.normals[v]))
                    return Error{where + ": vertex " + std::to_string(v) + " is not finite"};
        }
    }
    for (size_t k = 0; k < c.clips.size(); ++k) {
        const Clip& clip = c.clips[k];
        for (size_t ch = 0; ch < clip.channels.size(); ++ch) {
            const Channel& channel = clip.channels[ch];
            const std::string where =
                "clips[" + std::to_string(k) + "].channels[" + std::to_string(ch) + "]";
            if (channel.node < 0 || channel.node >= nodeCount)
                return Error{where + ": node " + std::to_string(channel.node) + " does not exist"};
            if (channel.times.empty()) return Error{where + ": no keys"};
            const size_t perKey = channel.interpolation == Interpolation::CubicSpline ? 3 : 1;
            if (channel.values.size() != perKey * channel.times.size())
                return Error{where + ": " + std::to_string(channel.values.size()) + " values for " +
                             std::to_string(channel.times.size()) + " keys"};
            for (size_t i = 0; i < channel.times.size(); ++i) {
                if (!std::isfinite(channel.times[i]) || channel.times[i] < 0.0f)
                    return Error{where + ": key time " + std::to_string(i) + " is not finite"};
                if (i > 0 && !(channel.times[i] > channel.times[i - 1]))
                    return Error{where + ": key times do not increase at key " + std::to_string(i)};
            }
            for (const glm::vec4& v : channel.values)
                if (!finite(v)) return Error{where + ": a value is not finite"};
        }
    }
    return Ok{};
}

void scaleCharacter(Character& character, float factor) {
    for (Node& node : character.nodes)
        node.rest.translation *= factor;
    for (Skin& skin : character.skins)
        for (glm::mat4& inverseBind : skin.inverseBind)
            inverseBind[3] = glm::vec4(glm::vec3(inverseBind[3]) * factor, inverseBind[3].w);
    for (Mesh& mesh : character.meshes)
        for (Primitive& p : mesh.primitives)
            for (glm::vec3& position : p.positions)
                position *= factor;
    for (Clip& clip : character.clips)
        for (Channel& channel : clip.channels)
            if (channel.path == Path::Translation)
                for (glm::vec4& value : channel.values)
                    value = glm::vec4(glm::vec3(value) * factor, value.w);
}

} // namespace mfx::anim
