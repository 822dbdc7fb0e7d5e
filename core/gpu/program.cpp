#include "core/gpu/program.h"

#include "core/gpu/check.h"
#include "core/gpu/context.h"
#include "core/gpu/resources.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace mfx::gpu {

namespace {

constexpr uint32_t kSpirvMagic = 0x07230203;
// Bindings per program: the push descriptors every desktop driver offers (maxPushDescriptors is at
// least 32), with binding numbers below 64 so one bit each marks them written.
constexpr size_t kMaxBindings = 32;
constexpr uint32_t kMaxBindingNumber = 64;

UniqueShaderModule createShaderModule(const Context& ctx, std::span<const uint32_t> spirv,
                                      const std::string& programName) {
    if (spirv.size() < 5 || spirv[0] != kSpirvMagic)
        throw std::logic_error("program " + programName + ": shader code is not SPIR-V");
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = spirv.size_bytes();
    info.pCode = spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreateShaderModule(ctx.device(), &info, nullptr, &module));
    return UniqueShaderModule(ctx.device(), module);
}

bool isImageType(VkDescriptorType type) {
    switch (type) {
    case VK_DESCRIPTOR_TYPE_SAMPLER:
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
    case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
    case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT:
        return true;
    default:
        return false;
    }
}

// The push-descriptor set layout and the pipeline layout of the program's binding table.
void buildLayout(const Context& ctx, const std::string& name,
                 const std::vector<BindingDesc>& bindings, uint32_t pushConstantSize,
                 VkShaderStageFlags pushStages, UniqueDescriptorSetLayout& setLayout,
                 UniquePipelineLayout& layout) {
    std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
    for (const BindingDesc& b : bindings) {
        if (b.binding >= kMaxBindingNumber)
            throw std::logic_error("program " + name + ": binding " + std::to_string(b.binding) +
                                   " is numbered " + std::to_string(kMaxBindingNumber) +
                                   " or more");
        layoutBindings.push_back({b.binding, b.type, 1, b.stages, nullptr});
    }
    if (layoutBindings.size() > std::min<size_t>(kMaxBindings, ctx.maxPushDescriptors()))
        throw std::logic_error("program " + name + ": " + std::to_string(layoutBindings.size()) +
                               " bindings exceed the device's " +
                               std::to_string(ctx.maxPushDescriptors()) + " push descriptors");
    VkDescriptorSetLayout setLayoutHandle = VK_NULL_HANDLE;
    if (!layoutBindings.empty()) {
        VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        info.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
        info.bindingCount = static_cast<uint32_t>(layoutBindings.size());
        info.pBindings = layoutBindings.data();
        MFX_VK_CHECK(vkCreateDescriptorSetLayout(ctx.device(), &info, nullptr, &setLayoutHandle));
        setLayout = UniqueDescriptorSetLayout(ctx.device(), setLayoutHandle);
    }

    VkPushConstantRange range{pushStages, 0, pushConstantSize};
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = setLayoutHandle != VK_NULL_HANDLE ? 1 : 0;
    info.pSetLayouts = &setLayoutHandle;
    info.pushConstantRangeCount = pushConstantSize > 0 ? 1 : 0;
    info.pPushConstantRanges = &range;
    if (pushConstantSize > ctx.limits().maxPushConstantsSize)
        throw std::logic_error("program " + name + ": " + std::to_string(pushConstantSize) +
                               " bytes of push constants exceed the device limit of " +
                               std::to_string(ctx.limits().maxPushConstantsSize));
    VkPipelineLayout layoutHandle = VK_NULL_HANDLE;
    MFX_VK_CHECK(vkCreatePipelineLayout(ctx.device(), &info, nullptr, &layoutHandle));
    layout = UniquePipelineLayout(ctx.device(), layoutHandle);
}

struct Specialization {
    std::vector<VkSpecializationMapEntry> entries;
    VkSpecializationInfo info{};

    explicit Specialization(const std::vector<uint32_t>& values) {
        for (uint32_t i = 0; i < values.size(); ++i)
            entries.push_back({i, i * uint32_t(sizeof(uint32_t)), sizeof(uint32_t)});
        info.mapEntryCount = static_cast<uint32_t>(entries.size());
        info.pMapEntries = entries.data();
        info.dataSize = values.size() * sizeof(uint32_t);
        info.pData = values.data();
    }
    const VkSpecializationInfo* get() const { return entries.empty() ? nullptr : &info; }
};

VkPipelineColorBlendAttachmentState blendState(BlendMode mode) {
    VkPipelineColorBlendAttachmentState state{};
    state.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                           VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    state.colorBlendOp = VK_BLEND_OP_ADD;
    state.alphaBlendOp = VK_BLEND_OP_ADD;
    // Colour and alpha: source and destination factors.
    auto blend = [&](VkBlendFactor src, VkBlendFactor dst, VkBlendFactor srcAlpha,
                     VkBlendFactor dstAlpha) {
        state.blendEnable = VK_TRUE;
        state.srcColorBlendFactor = src;
        state.dstColorBlendFactor = dst;
        state.srcAlphaBlendFactor = srcAlpha;
        state.dstAlphaBlendFactor = dstAlpha;
    };
    constexpr VkBlendFactor one = VK_BLEND_FACTOR_ONE, zero = VK_BLEND_FACTOR_ZERO;
    constexpr VkBlendFactor srcA = VK_BLEND_FACTOR_SRC_ALPHA,
                            oneMinusSrcA = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    switch (mode) {
    case BlendMode::Opaque:
        state.blendEnable = VK_FALSE;
        break;
    case BlendMode::Alpha:
        blend(srcA, oneMinusSrcA, one, oneMinusSrcA);
        break;
    case BlendMode::PremultipliedAlpha:
        blend(one, oneMinusSrcA, one, oneMinusSrcA);
        break;
    case BlendMode::Additive:
        blend(srcA, one, zero, one);
        break;
    }
    return state;
}

} // namespace

DescriptorWrite bindBuffer(uint32_t binding, const Buffer& buffer, VkDeviceSize offset,
                           VkDeviceSize range) {
    DescriptorWrite write;
    write.binding = binding;
    write.buffer = {buffer.get(), offset, range};
    return write;
}

std::vector<DescriptorWrite>
bindBuffers(std::initializer_list<std::reference_wrapper<const Buffer>> buffers) {
    std::vector<DescriptorWrite> writes;
    for (const Buffer& buffer : buffers)
        writes.push_back(bindBuffer(uint32_t(writes.size()), buffer));
    return writes;
}

DescriptorWrite bindImage(uint32_t binding, const Image& image, VkImageLayout layout,
                          VkSampler sampler) {
    DescriptorWrite write;
    write.binding = binding;
    write.image = {sampler, image.view.get(), layout};
    write.isImage = true;
    return write;
}

namespace {

// A program's shader code by its length and an FNV-1a hash of its words.
std::string spirvKey(std::span<const uint32_t> spirv) {
    uint64_t h = 1469598103934665603ull;
    for (uint32_t word : spirv)
        for (int byte = 0; byte < 4; ++byte) {
            h ^= (word >> (8 * byte)) & 0xffu;
            h *= 1099511628211ull;
        }
    return std::to_string(spirv.size()) + ":" + std::to_string(h);
}

// Everything a graphics program is made from, as one string.
std::string graphicsKey(const GraphicsProgramDesc& d) {
    std::ostringstream key;
    key << "graphics|" << d.name << '|' << spirvKey(d.vertex) << '|' << spirvKey(d.geometry) << '|'
        << spirvKey(d.fragment) << '|' << d.pushConstantSize << '|';
    for (uint32_t v : d.specialization)
        key << v << ',';
    key << '|' << d.vertexStride << '|';
    for (const VertexAttribute& a : d.attributes)
        key << a.location << ':' << a.format << ':' << a.offset << ',';
    key << '|' << d.topology << '|' << d.polygonMode << '|' << d.cullMode << '|' << d.frontFace
        << '|' << d.rasterizerDiscard << '|';
    for (VkFormat f : d.colorFormats)
        key << f << ',';
    key << '|' << d.depthFormat << '|' << d.depthTest << d.depthWrite << '|' << d.depthCompare
        << '|' << int(d.blend) << '|' << d.samples;
    return key.str();
}

} // namespace

Program createComputeProgram(const Context& ctx, const ComputeProgramDesc& desc) {
    Program program;
    program.name_ = desc.name;
    program.bindings_ = spirvBindings(desc.spirv, VK_SHADER_STAGE_COMPUTE_BIT, program.name_);
    program.pushConstantSize_ = desc.pushConstantSize;
    program.pushStages_ = VK_SHADER_STAGE_COMPUTE_BIT;
    program.bindPoint_ = VK_PIPELINE_BIND_POINT_COMPUTE;
    program.pushDescriptors_ = ctx.cmdPushDescriptorSet();
    std::ostringstream key;
    key << "compute|" << desc.name << '|' << spirvKey(desc.spirv) << '|' << desc.pushConstantSize
        << '|';
    for (uint32_t v : desc.specialization)
        key << v << ',';
    if ((program.objects_ = ctx.findProgram(key.str()))) return program;
    auto objects = std::make_shared<ProgramObjects>();
    buildLayout(ctx, program.name_, program.bindings_, desc.pushConstantSize, program.pushStages_,
                objects->setLayout, objects->layout);

    UniqueShaderModule module = createShaderModule(ctx, desc.spirv, program.name_);
    const Specialization specialization(desc.specialization);
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module.get();
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = specialization.get();
    info.layout = objects->layout.get();
    VkPipeline pipeline = VK_NULL_HANDLE;
    MFX_VK_CHECK(
        vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    objects->pipeline = UniquePipeline(ctx.device(), pipeline);
    program.objects_ = objects;
    ctx.keepProgram(key.str(), objects);
    ctx.setDebugName(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(pipeline), desc.name);
    return program;
}

Program createGraphicsProgram(const Context& ctx, const GraphicsProgramDesc& desc) {
    if (!desc.geometry.empty() && !ctx.features().geometryShader)
        throw std::logic_error("program " + std::string(desc.name) +
                               " needs geometry shaders, which " + ctx.info().name + " lacks");
    Program program;
    program.name_ = desc.name;
    std::vector<std::vector<BindingDesc>> stageBindings;
    stageBindings.push_back(spirvBindings(desc.vertex, VK_SHADER_STAGE_VERTEX_BIT, program.name_));
    if (!desc.geometry.empty())
        stageBindings.push_back(
            spirvBindings(desc.geometry, VK_SHADER_STAGE_GEOMETRY_BIT, program.name_));
    if (!desc.fragment.empty())
        stageBindings.push_back(
            spirvBindings(desc.fragment, VK_SHADER_STAGE_FRAGMENT_BIT, program.name_));
    program.bindings_ = mergeBindings(stageBindings, program.name_);
    program.pushConstantSize_ = desc.pushConstantSize;
    program.pushStages_ = VK_SHADER_STAGE_VERTEX_BIT;
    if (!desc.geometry.empty()) program.pushStages_ |= VK_SHADER_STAGE_GEOMETRY_BIT;
    if (!desc.fragment.empty()) program.pushStages_ |= VK_SHADER_STAGE_FRAGMENT_BIT;
    program.bindPoint_ = VK_PIPELINE_BIND_POINT_GRAPHICS;
    program.pushDescriptors_ = ctx.cmdPushDescriptorSet();
    const std::string key = graphicsKey(desc);
    if ((program.objects_ = ctx.findProgram(key))) return program;
    auto objects = std::make_shared<ProgramObjects>();
    buildLayout(ctx, program.name_, program.bindings_, desc.pushConstantSize, program.pushStages_,
                objects->setLayout, objects->layout);

    const Specialization specialization(desc.specialization);
    std::vector<UniqueShaderModule> modules;
    std::vector<VkPipelineShaderStageCreateInfo> stages;
    auto addStage = [&](std::span<const uint32_t> spirv, VkShaderStageFlagBits stage) {
        if (spirv.empty()) return;
        modules.push_back(createShaderModule(ctx, spirv, program.name_));
        VkPipelineShaderStageCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        info.stage = stage;
        info.module = modules.back().get();
        info.pName = "main";
        info.pSpecializationInfo = specialization.get();
        stages.push_back(info);
    };
    addStage(desc.vertex, VK_SHADER_STAGE_VERTEX_BIT);
    addStage(desc.geometry, VK_SHADER_STAGE_GEOMETRY_BIT);
    addStage(desc.fragment, VK_SHADER_STAGE_FRAGMENT_BIT);

    VkVertexInputBindingDescription vertexBinding{0, desc.vertexStride,
                                                  VK_VERTEX_INPUT_RATE_VERTEX};
    std::vector<VkVertexInputAttributeDescription> attributes;
    for (const VertexAttribute& a : desc.attributes)
        attributes.push_back({a.location, 0, a.format, a.offset});
    VkPipelineVertexInputStateCreateInfo vertexInput{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertexInput.vertexBindingDescriptionCount = desc.vertexStride > 0 ? 1 : 0;
    vertexInput.pVertexBindingDescriptions = &vertexBinding;
    vertexInput.vertexAttributeDescriptionCount = static_cast<uint32_t>(attributes.size());
    vertexInput.pVertexAttributeDescriptions = attributes.data();

    VkPipelineInputAssemblyStateCreateInfo inputAssembly{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    inputAssembly.topology = desc.topology;

    VkPipelineViewportStateCreateInfo viewport{
        VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;

    VkPipelineRasterizationStateCreateInfo raster{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = desc.polygonMode;
    raster.cullMode = desc.cullMode;
    raster.frontFace = desc.frontFace;
    raster.lineWidth = 1.0f;
    raster.rasterizerDiscardEnable = desc.rasterizerDiscard ? VK_TRUE : VK_FALSE;

    VkPipelineMultisampleStateCreateInfo multisample{
        VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = desc.samples;

    VkPipelineDepthStencilStateCreateInfo depth{
        VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = desc.depthTest ? VK_TRUE : VK_FALSE;
    depth.depthWriteEnable = desc.depthWrite ? VK_TRUE : VK_FALSE;
    depth.depthCompareOp = desc.depthCompare;

    std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size(),
                                                            blendState(desc.blend));
    VkPipelineColorBlendStateCreateInfo blend{
        VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = static_cast<uint32_t>(blends.size());
    blend.pAttachments = blends.data();

    const VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamicStates;

    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = static_cast<uint32_t>(desc.colorFormats.size());
    rendering.pColorAttachmentFormats = desc.colorFormats.data();
    rendering.depthAttachmentFormat = desc.depthFormat;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.pNext = &rendering;
    info.stageCount = static_cast<uint32_t>(stages.size());
    info.pStages = stages.data();
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &inputAssembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = objects->layout.get();
    VkPipeline pipeline = VK_NULL_HANDLE;
    MFX_VK_CHECK(
        vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    objects->pipeline = UniquePipeline(ctx.device(), pipeline);
    program.objects_ = objects;
    ctx.keepProgram(key, objects);
    ctx.setDebugName(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(pipeline), desc.name);
    return program;
}

void Program::bind(VkCommandBuffer cmd, std::span<const DescriptorWrite> writes) const {
    // At most a few dozen bindings: a linear search beats a map here.
    auto declared = [&](uint32_t binding) -> const BindingDesc* {
        for (const BindingDesc& b : bindings_)
            if (b.binding == binding) return &b;
        return nullptr;
    };
    auto fail = [&](uint32_t binding, const char* what) {
        throw std::logic_error("program " + name_ + ": binding " + std::to_string(binding) + what);
    };
    VkWriteDescriptorSet vkWrites[kMaxBindings];
    if (writes.size() > kMaxBindings) fail(writes.back().binding, " is beyond the binding limit");
    uint64_t written = 0;
    for (size_t i = 0; i < writes.size(); ++i) {
        const DescriptorWrite& w = writes[i];
        const BindingDesc* b = declared(w.binding);
        if (b == nullptr) fail(w.binding, " is not declared by the program's shaders");
        const uint64_t bit = uint64_t(1) << w.binding; // declared, so below 64
        if ((written & bit) != 0) fail(w.binding, " is written twice");
        written |= bit;
        if (w.isImage != isImageType(b->type))
            fail(w.binding, w.isImage ? " declares a buffer but got an image"
                                      : " declares an image but got a buffer");
        if (b->type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER &&
            w.image.sampler == VK_NULL_HANDLE)
            fail(w.binding, " needs a sampler");
        VkWriteDescriptorSet& write = vkWrites[i];
        write = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        write.dstBinding = w.binding;
        write.descriptorCount = 1;
        write.descriptorType = b->type;
        write.pBufferInfo = w.isImage ? nullptr : &w.buffer;
        write.pImageInfo = w.isImage ? &w.image : nullptr;
    }
    if (writes.size() != bindings_.size())
        for (const BindingDesc& b : bindings_)
            if ((written & (uint64_t(1) << b.binding)) == 0)
                fail(b.binding, " is declared but not written");
    vkCmdBindPipeline(cmd, bindPoint_, pipeline());
    if (!writes.empty())
        pushDescriptors_(cmd, bindPoint_, layout(), 0, static_cast<uint32_t>(writes.size()),
                         vkWrites);
}

void Program::bindPipeline(VkCommandBuffer cmd) const {
    vkCmdBindPipeline(cmd, bindPoint_, pipeline());
}

void Program::push(VkCommandBuffer cmd, const void* data, uint32_t size) const {
    if (size != pushConstantSize_)
        throw std::logic_error("program " + name_ + ": pushed " + std::to_string(size) +
                               " bytes, declared " + std::to_string(pushConstantSize_));
    vkCmdPushConstants(cmd, layout(), pushStages_, 0, size, data);
}

} // namespace mfx::gpu
