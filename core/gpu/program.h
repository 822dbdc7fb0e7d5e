// Programs: a pipeline together with its layout, built from embedded SPIR-V. The binding table is
// read from the SPIR-V itself (core/gpu/spirv_bindings.h), so the shader is the one description of
// a program's resources. Resources are pushed when the program is bound (VK_KHR_push_descriptor):
// there are no descriptor sets to allocate, cache or free, and every push is checked against the
// table (each binding written once, with a resource of the right kind).
//
// Compute, graphics, and graphics with a geometry stage. Graphics programs use dynamic rendering
// (no render pass objects) with dynamic viewport and scissor.
#pragma once

#include "core/gpu/handle.h"
#include "core/gpu/spirv_bindings.h"

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

namespace mfx::gpu {

class Context;
struct Buffer;
struct Image;

// One resource bound to one binding of a set.
struct DescriptorWrite {
    uint32_t binding = 0;
    VkDescriptorBufferInfo buffer{};
    VkDescriptorImageInfo image{};
    bool isImage = false;
};

DescriptorWrite bindBuffer(uint32_t binding, const Buffer& buffer, VkDeviceSize offset = 0,
                           VkDeviceSize range = VK_WHOLE_SIZE);
// Whole buffers at bindings 0, 1, 2, ... in the order given.
std::vector<DescriptorWrite>
bindBuffers(std::initializer_list<std::reference_wrapper<const Buffer>> buffers);
// `layout` is the layout the image will be in when the set is used (GENERAL for storage images,
// SHADER_READ_ONLY_OPTIMAL for sampled ones).
DescriptorWrite bindImage(uint32_t binding, const Image& image, VkImageLayout layout,
                          VkSampler sampler = VK_NULL_HANDLE);

struct ComputeProgramDesc {
    const char* name = "compute";
    std::span<const uint32_t> spirv;
    uint32_t pushConstantSize = 0;
    // Specialization constants: constant_id i gets specialization[i] (32-bit each; floats by
    // std::bit_cast).
    std::vector<uint32_t> specialization;
};

enum class BlendMode { Opaque, Alpha, PremultipliedAlpha, Additive };

struct VertexAttribute {
    uint32_t location = 0;
    VkFormat format = VK_FORMAT_R32G32B32_SFLOAT;
    uint32_t offset = 0;
};

struct GraphicsProgramDesc {
    const char* name = "graphics";
    std::span<const uint32_t> vertex;
    std::span<const uint32_t> geometry;   // empty: no geometry stage
    std::span<const uint32_t> fragment;   // empty: no fragment stage (depth-only, or discard)
    uint32_t pushConstantSize = 0;        // visible to every stage the program has
    std::vector<uint32_t> specialization; // shared by all stages

    uint32_t vertexStride = 0; // 0: no vertex buffer (vertices generated in the shader)
    std::vector<VertexAttribute> attributes;
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPolygonMode polygonMode = VK_POLYGON_MODE_FILL;
    VkCullModeFlags cullMode = VK_CULL_MODE_NONE;
    VkFrontFace frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    bool rasterizerDiscard = false; // transform feedback without drawing

    std::vector<VkFormat> colorFormats;
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    bool depthTest = false;
    bool depthWrite = false;
    VkCompareOp depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
    BlendMode blend = BlendMode::Opaque;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
};

// A program's Vulkan objects. A Context keeps those it made, by the program's description, and
// gives them to every program built again from the same description (Context::findProgram):
// lavapipe compiles a pipeline's shaders at its first use, so a viewer rebuilding its scene
// would otherwise compile every shader again.
struct ProgramObjects {
    UniqueDescriptorSetLayout setLayout;
    UniquePipelineLayout layout;
    UniquePipeline pipeline;
};

class Program {
public:
    Program() = default;

    VkPipeline pipeline() const { return objects_ ? objects_->pipeline.get() : VK_NULL_HANDLE; }
    VkPipelineLayout layout() const { return objects_ ? objects_->layout.get() : VK_NULL_HANDLE; }
    VkPipelineBindPoint bindPoint() const { return bindPoint_; }
    const std::vector<BindingDesc>& bindings() const { return bindings_; }
    uint32_t pushConstantSize() const { return pushConstantSize_; }
    const std::string& name() const { return name_; }

    // Binds the pipeline and pushes `writes` as its resources, for the dispatches and draws that
    // follow. Every binding of the shaders must be written exactly once with a resource of its
    // kind; anything else throws std::logic_error naming the program and the binding.
    void bind(VkCommandBuffer cmd, std::span<const DescriptorWrite> writes = {}) const;
    void bind(VkCommandBuffer cmd, std::initializer_list<DescriptorWrite> writes) const {
        bind(cmd, std::span<const DescriptorWrite>(writes.begin(), writes.size()));
    }
    // Binds the pipeline alone, keeping the resources pushed last: only right after bind(cmd,
    // writes) of a program with the same bindings and push constants in the same command buffer
    // (a compatible layout), with nothing pushed or bound in between by another program.
    void bindPipeline(VkCommandBuffer cmd) const;
    // Pushes `size` bytes; must equal the declared push constant size.
    void push(VkCommandBuffer cmd, const void* data, uint32_t size) const;
    template <typename T>
    void push(VkCommandBuffer cmd, const T& constants) const {
        push(cmd, &constants, static_cast<uint32_t>(sizeof(T)));
    }

    friend Program createComputeProgram(const Context& ctx, const ComputeProgramDesc& desc);
    friend Program createGraphicsProgram(const Context& ctx, const GraphicsProgramDesc& desc);

private:
    std::string name_;
    std::vector<BindingDesc> bindings_;
    uint32_t pushConstantSize_ = 0;
    VkShaderStageFlags pushStages_ = 0;
    VkPipelineBindPoint bindPoint_ = VK_PIPELINE_BIND_POINT_COMPUTE;
    std::shared_ptr<const ProgramObjects> objects_;
    PFN_vkCmdPushDescriptorSetKHR pushDescriptors_ = nullptr;
};

Program createComputeProgram(const Context& ctx, const ComputeProgramDesc& desc);
Program createGraphicsProgram(const Context& ctx, const GraphicsProgramDesc& desc);

// Number of workgroups of `groupSize` covering `count` items.
constexpr uint32_t groupCount(uint32_t count, uint32_t groupSize) {
    return (count + groupSize - 1) / groupSize;
}

} // namespace mfx::gpu
