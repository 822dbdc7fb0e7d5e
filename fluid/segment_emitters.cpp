// Twin of shaders/fluid/segment_emitters.comp; keep the arithmetic the same.
#include "fluid/segment_emitters.h"

#include "shaders/embedded.h"

#include <algorithm>

namespace mfx::fluid {

uint32_t emitterCount(uint32_t vertexCount, const CouplingParameters& parameters) {
    if (vertexCount <= parameters.maxEmitters) return vertexCount;
    const uint32_t perVertex = std::max(parameters.samplesPerVertex, 1u);
    return std::min(vertexCount, std::max(parameters.maxEmitters / perVertex, 1u) * perVertex);
}

std::vector<shared::FluidEmitter> segmentEmitters(std::span<const shared::TrajectoryVertex> segment,
                                                  const CouplingParameters& parameters) {
    const uint32_t count = emitterCount(uint32_t(segment.size()), parameters);
    std::vector<shared::FluidEmitter> out(count);
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t perVertex = std::max(parameters.samplesPerVertex, 1u);
        const uint32_t sources = uint32_t(segment.size()) / perVertex;
        const uint32_t picked = std::max(count / perVertex, 1u);
        const uint32_t source = uint32_t(float(i / perVertex) * (float(sources) / float(picked)));
        const size_t j = std::min<size_t>(source * perVertex + i % perVertex, segment.size() - 1);
        const shared::TrajectoryVertex& v = segment[j];
        out[i].positionRadius =
            glm::vec4(glm::vec3(v.position) - parameters.gridOrigin, parameters.radius);
        out[i].velocityStrength = glm::vec4(glm::vec3(v.velocity), parameters.strength * v.color.a);
        out[i].pigment = glm::vec4(glm::vec3(v.color), 1.0f);
    }
    return out;
}

SegmentEmitters::SegmentEmitters(const gpu::Context& ctx) {
    gpu::ComputeProgramDesc desc;
    desc.name = "segment_emitters";
    desc.spirv = shaders::segment_emitters_comp;
    desc.pushConstantSize = sizeof(shared::SegmentEmitterConstants);
    program_ = gpu::createComputeProgram(ctx, desc);
}

uint32_t SegmentEmitters::record(VkCommandBuffer cmd, const gpu::Buffer& ring, uint32_t firstVertex,
                                 uint32_t vertexCount, const gpu::Buffer& emitters,
                                 uint32_t firstEmitter, const CouplingParameters& parameters) {
    const uint32_t count = emitterCount(vertexCount, parameters);
    if (count == 0) return 0;
    shared::SegmentEmitterConstants c{};
    c.gridOrigin = glm::vec4(parameters.gridOrigin, parameters.radius);
    c.firstVertex = firstVertex;
    c.vertexCount = vertexCount;
    c.emitterCount = count;
    c.firstEmitter = firstEmitter;
    c.strength = parameters.strength;
    c.samplesPerVertex = parameters.samplesPerVertex;
    program_.bind(cmd, {gpu::bindBuffer(0, ring), gpu::bindBuffer(1, emitters)});
    program_.push(cmd, c);
    vkCmdDispatch(cmd, gpu::groupCount(count, MFX_COUPLING_GROUP_SIZE), 1, 1);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    return count;
}

} // namespace mfx::fluid
