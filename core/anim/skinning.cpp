#include "core/anim/skinning.h"

namespace mfx::anim {

std::vector<DualQuatJoint> dualQuatPalette(const std::vector<glm::mat4>& jointMatrices) {
    std::vector<DualQuatJoint> palette;
    palette.reserve(jointMatrices.size());
    for (const glm::mat4& m : jointMatrices) {
        const math::Decomposed d = math::decompose(m);
        palette.push_back({math::DualQuat::fromRigid(d.rotation, d.translation), d.scale});
    }
    return palette;
}

DualQuatJoint blendJoints(const std::vector<DualQuatJoint>& palette, glm::uvec4 joints,
                          glm::vec4 weights) {
    int first = 0;
    while (first < 3 && !(weights[first] > 0.0f))
        ++first;
    if (!(weights[first] > 0.0f)) return {}; // no influence: the identity
    const math::DualQuat& reference = palette[joints[first]].rigid;
    math::DualQuat blended{glm::quat(0.0f, 0.0f, 0.0f, 0.0f), glm::quat(0.0f, 0.0f, 0.0f, 0.0f)};
    glm::vec3 scale(0.0f);
    float total = 0.0f;
    for (int k = 0; k < 4; ++k) {
        if (!(weights[k] > 0.0f)) continue;
        const DualQuatJoint& joint = palette[joints[k]];
        blended = blended + weights[k] * math::alignedWith(joint.rigid, reference);
        scale += weights[k] * joint.scale;
        total += weights[k];
    }
    scale /= total; // weights that do not sum to 1 still blend the scale as an average
    return {blended.normalized(), scale};
}

SkinnedVertex applyTransform(const DualQuatJoint& transform, glm::vec3 position, glm::vec3 normal) {
    SkinnedVertex out;
    out.position = transform.rigid.transformPoint(transform.scale * position);
    out.normal = glm::normalize(transform.rigid.transformVector(normal / transform.scale));
    return out;
}

SkinnedVertex skinDualQuat(const std::vector<DualQuatJoint>& palette, glm::vec3 position,
                           glm::vec3 normal, glm::uvec4 joints, glm::vec4 weights) {
    return applyTransform(blendJoints(palette, joints, weights), position, normal);
}

SkinnedVertex skinLinear(const std::vector<glm::mat4>& jointMatrices, glm::vec3 position,
                         glm::vec3 normal, glm::uvec4 joints, glm::vec4 weights) {
    glm::mat4 m(0.0f);
    for (int k = 0; k < 4; ++k)
        if (weights[k] > 0.0f) m += weights[k] * jointMatrices[joints[k]];
    SkinnedVertex out;
    out.position = glm::vec3(m * glm::vec4(position, 1.0f));
    out.normal = glm::normalize(glm::transpose(glm::inverse(glm::mat3(m))) * normal);
    return out;
}

std::vector<SkinnedVertex> skinPrimitive(const Character& character, const Primitive& primitive,
                                         const Pose& pose, SkinningMethod method) {
    const size_t count = primitive.positions.size();
    std::vector<SkinnedVertex> out(count);
    if (primitive.skin < 0) {
        const glm::mat4 m =
            primitive.node < 0 ? glm::mat4(1.0f) : pose.world[size_t(primitive.node)];
        const glm::mat3 n = glm::transpose(glm::inverse(glm::mat3(m)));
        for (size_t v = 0; v < count; ++v)
            out[v] = {glm::vec3(m * glm::vec4(primitive.positions[v], 1.0f)),
                      glm::normalize(n * primitive.normals[v])};
        return out;
    }
    const std::vector<glm::mat4> matrices = jointMatrices(character, primitive.skin, pose);
    if (method == SkinningMethod::Linear) {
        for (size_t v = 0; v < count; ++v)
            out[v] = skinLinear(matrices, primitive.positions[v], primitive.normals[v],
                                primitive.joints[v], primitive.weights[v]);
        return out;
    }
    const std::vector<DualQuatJoint> palette = dualQuatPalette(matrices);
    for (size_t v = 0; v < count; ++v)
        out[v] = skinDualQuat(palette, primitive.positions[v], primitive.normals[v],
                              primitive.joints[v], primitive.weights[v]);
    return out;
}

} // namespace mfx::anim
