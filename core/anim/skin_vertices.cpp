#include "core/anim/skin_vertices.h"

#include "shaders/embedded.h"

namespace mfx::anim {

std::vector<shared::SkinJoint> packPalette(const std::vector<DualQuatJoint>& palette) {
    std::vector<shared::SkinJoint> packed;
    packed.reserve(palette.size());
    for (const DualQuatJoint& j : palette) {
        const glm::quat& r = j.rigid.real;
        const glm::quat& d = j.rigid.dual;
        packed.push_back({glm::vec4(r.x, r.y, r.z, r.w), glm::vec4(d.x, d.y, d.z, d.w),
                          glm::vec4(j.scale, 0.0f)});
    }
    return packed;
}

std::vector<shared::SkinVertexIn> packVertices(const Primitive& primitive) {
    const bool skinned = !primitive.joints.empty();
    std::vector<shared::SkinVertexIn> packed(primitive.positions.size());
    for (size_t v = 0; v < packed.size(); ++v) {
        packed[v].position = glm::vec4(primitive.positions[v], 1.0f);
        packed[v].normal = glm::vec4(primitive.normals[v], 0.0f);
        packed[v].joints = skinned ? primitive.joints[v] : glm::uvec4(0);
        packed[v].weights = skinned ? primitive.weights[v] : glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
    }
    return packed;
}

SkinVertices::SkinVertices(const gpu::Context& ctx) {
    gpu::ComputeProgramDesc desc;
    desc.name = "skin_vertices";
    desc.spirv = shaders::skin_vertices_comp;
    desc.pushConstantSize = sizeof(shared::SkinConstants);
    program_ = gpu::createComputeProgram(ctx, desc);
}

void SkinVertices::record(VkCommandBuffer cmd, const gpu::Buffer& palette, uint32_t jointCount,
                          const gpu::Buffer& input, const gpu::Buffer& output,
                          uint32_t vertexCount) {
    if (vertexCount == 0) return;
    program_.bind(
        cmd, {gpu::bindBuffer(0, palette), gpu::bindBuffer(1, input), gpu::bindBuffer(2, output)});
    program_.push(cmd, shared::SkinConstants{vertexCount, jointCount, 0, 0});
    vkCmdDispatch(cmd, gpu::groupCount(vertexCount, MFX_SKIN_GROUP_SIZE), 1, 1);
    gpu::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_INPUT_BIT |
            VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT |
            VK_ACCESS_2_TRANSFER_READ_BIT);
}

} // namespace mfx::anim
