#include "core/gpu/spirv_bindings.h"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace mfx::gpu {

namespace {

// The numbers of the SPIR-V specification this reader needs (sections 3.x and the opcode table).
constexpr uint32_t kMagic = 0x07230203;
constexpr uint32_t kHeaderWords = 5;
enum Op : uint32_t {
    OpTypeImage = 25,
    OpTypeSampler = 26,
    OpTypeSampledImage = 27,
    OpTypeArray = 28,
    OpTypeRuntimeArray = 29,
    OpTypeStruct = 30,
    OpTypePointer = 32,
    OpVariable = 59,
    OpDecorate = 71,
};
enum Decoration : uint32_t { Block = 2, BufferBlock = 3, Binding = 33, DescriptorSet = 34 };
enum StorageClass : uint32_t { UniformConstant = 0, Uniform = 2, StorageBuffer = 12 };
constexpr uint32_t kDimBuffer = 5, kImageSampled = 1, kImageStorage = 2;

struct Variable {
    uint32_t pointerType = 0;
    uint32_t storageClass = 0;
};

} // namespace

std::vector<BindingDesc> spirvBindings(std::span<const uint32_t> spirv, VkShaderStageFlags stage,
                                       const std::string& programName) {
    auto fail = [&](const std::string& what) {
        throw std::logic_error("program " + programName + ": " + what);
    };
    if (spirv.size() < kHeaderWords || spirv[0] != kMagic) fail("shader code is not SPIR-V");

    std::map<uint32_t, uint32_t> bindingOf, setOf;   // id → decoration value
    std::map<uint32_t, uint32_t> blockKind;          // struct id → Block or BufferBlock
    std::map<uint32_t, std::vector<uint32_t>> types; // type id → its instruction's operands
    std::map<uint32_t, uint32_t> opOf;               // type id → its opcode
    std::map<uint32_t, Variable> variables;
    for (size_t at = kHeaderWords; at < spirv.size();) {
        const uint32_t words = spirv[at] >> 16, op = spirv[at] & 0xffffu;
        if (words == 0 || at + words > spirv.size()) fail("malformed SPIR-V instruction");
        const std::span<const uint32_t> operands = spirv.subspan(at + 1, words - 1);
        at += words;
        switch (op) {
        case OpDecorate:
            if (operands.size() >= 3 && operands[1] == Binding)
                bindingOf[operands[0]] = operands[2];
            if (operands.size() >= 3 && operands[1] == DescriptorSet)
                setOf[operands[0]] = operands[2];
            if (operands.size() >= 2 && (operands[1] == Block || operands[1] == BufferBlock))
                blockKind[operands[0]] = operands[1];
            break;
        case OpTypeImage:
        case OpTypeSampler:
        case OpTypeSampledImage:
        case OpTypeArray:
        case OpTypeRuntimeArray:
        case OpTypeStruct:
        case OpTypePointer:
            if (!operands.empty()) {
                opOf[operands[0]] = op;
                types[operands[0]].assign(operands.begin() + 1, operands.end());
            }
            break;
        case OpVariable:
            if (operands.size() >= 3) variables[operands[1]] = {operands[0], operands[2]};
            break;
        default:
            break;
        }
    }

    std::vector<BindingDesc> out;
    for (const auto& [id, binding] : bindingOf) {
        auto variable = variables.find(id);
        if (variable == variables.end()) continue; // a decorated non-variable (not in glslang)
        const std::string where = "binding " + std::to_string(binding);
        if (setOf[id] != 0)
            fail(where + " is in descriptor set " + std::to_string(setOf[id]) +
                 "; programs use set 0 only");
        const std::vector<uint32_t>& pointer = types[variable->second.pointerType];
        if (opOf[variable->second.pointerType] != OpTypePointer || pointer.size() < 2)
            fail(where + " is not a pointer variable");
        const uint32_t pointee = pointer[1];
        const uint32_t kind = opOf[pointee];
        const std::vector<uint32_t>& type = types[pointee];
        VkDescriptorType descriptor{};
        switch (kind) {
        case OpTypeStruct:
            if (variable->second.storageClass == StorageBuffer ||
                (variable->second.storageClass == Uniform && blockKind[pointee] == BufferBlock))
                descriptor = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            else if (variable->second.storageClass == Uniform)
                descriptor = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
            else
                fail(where + " is a block in an unexpected storage class");
            break;
        case OpTypeImage:
            // operands after the result: sampled type, Dim, Depth, Arrayed, MS, Sampled, Format
            if (type.size() < 6 || type[1] == kDimBuffer) fail(where + " is a texel buffer");
            if (type[5] == kImageStorage)
                descriptor = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
            else if (type[5] == kImageSampled)
                descriptor = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
            else
                fail(where + " is an image of unknown use");
            break;
        case OpTypeSampledImage:
            descriptor = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            break;
        case OpTypeSampler:
            descriptor = VK_DESCRIPTOR_TYPE_SAMPLER;
            break;
        case OpTypeArray:
        case OpTypeRuntimeArray:
            fail(where + " is an array of resources; bind one resource per binding");
            break;
        default:
            fail(where + " is of a kind of resource programs do not bind");
        }
        if (variable->second.storageClass != UniformConstant &&
            variable->second.storageClass != Uniform &&
            variable->second.storageClass != StorageBuffer)
            fail(where + " is in an unexpected storage class");
        out.push_back({binding, descriptor, stage});
    }
    std::sort(out.begin(), out.end(),
              [](const BindingDesc& a, const BindingDesc& b) { return a.binding < b.binding; });
    for (size_t i = 1; i < out.size(); ++i)
        if (out[i].binding == out[i - 1].binding)
            fail("binding " + std::to_string(out[i].binding) + " is declared twice");
    return out;
}

std::vector<BindingDesc> mergeBindings(const std::vector<std::vector<BindingDesc>>& stages,
                                       const std::string& programName) {
    std::map<uint32_t, BindingDesc> merged;
    for (const std::vector<BindingDesc>& stage : stages)
        for (const BindingDesc& b : stage) {
            auto [it, added] = merged.emplace(b.binding, b);
            if (added) continue;
            if (it->second.type != b.type)
                throw std::logic_error("program " + programName + ": binding " +
                                       std::to_string(b.binding) +
                                       " is a different kind of resource in two stages");
            it->second.stages |= b.stages;
        }
    std::vector<BindingDesc> out;
    for (const auto& [binding, desc] : merged)
        out.push_back(desc);
    return out;
}

} // namespace mfx::gpu
