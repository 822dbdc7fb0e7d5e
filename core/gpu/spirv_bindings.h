// The resource bindings a shader declares, read from its SPIR-V: the one source of a program's
// binding layout (docs/architecture.md, "Binding GPU resources"). Follows the SPIR-V
// specification's physical layout (section 2.3: a five-word header, then instructions whose first
// word holds the word count and the opcode) and its decorations DescriptorSet and Binding.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

namespace mfx::gpu {

struct BindingDesc {
    uint32_t binding = 0;
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    VkShaderStageFlags stages = VK_SHADER_STAGE_ALL;
};

// Every variable of `spirv` with a DescriptorSet and Binding decoration, sorted by binding, with
// `stage` as its stages: uniform and storage buffers, storage and sampled images, samplers and
// combined image samplers. Throws std::logic_error naming `programName` for code that is not
// SPIR-V, a set other than 0, an array of resources, or a kind of resource the project does not
// bind.
std::vector<BindingDesc> spirvBindings(std::span<const uint32_t> spirv, VkShaderStageFlags stage,
                                       const std::string& programName);

// The bindings of several stages of one program: one entry per binding with the union of their
// stages. A binding whose kind differs between stages throws std::logic_error.
std::vector<BindingDesc> mergeBindings(const std::vector<std::vector<BindingDesc>>& stages,
                                       const std::string& programName);

} // namespace mfx::gpu
