// Binding tables read from SPIR-V (core/gpu/spirv_bindings.h): the kinds of resource the project's
// shaders declare, the union of stages, and refusals of what is not SPIR-V.
#include "core/gpu/spirv_bindings.h"
#include "shaders/embedded.h"
#include "test_shaders/embedded.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace mfx::test {
namespace {

using gpu::BindingDesc;

void expectBinding(const BindingDesc& b, uint32_t binding, VkDescriptorType type,
                   VkShaderStageFlags stages) {
    EXPECT_EQ(b.binding, binding);
    EXPECT_EQ(b.type, type) << "binding " << binding;
    EXPECT_EQ(b.stages, stages) << "binding " << binding;
}

TEST(SpirvBindings, StorageBuffersOfAComputeShader) {
    const auto bindings =
        gpu::spirvBindings(test_shaders::selftest_saxpy_comp, VK_SHADER_STAGE_COMPUTE_BIT, "saxpy");
    ASSERT_EQ(bindings.size(), 2u);
    expectBinding(bindings[0], 0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
    expectBinding(bindings[1], 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
}

TEST(SpirvBindings, StorageImage) {
    const auto bindings = gpu::spirvBindings(test_shaders::selftest_fill_volume_comp,
                                             VK_SHADER_STAGE_COMPUTE_BIT, "fill");
    ASSERT_EQ(bindings.size(), 1u);
    expectBinding(bindings[0], 0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT);
}

TEST(SpirvBindings, CombinedImageSamplerAndBuffers) {
    const auto bindings = gpu::spirvBindings(test_shaders::selftest_sample_volume_comp,
                                             VK_SHADER_STAGE_COMPUTE_BIT, "sample");
    ASSERT_EQ(bindings.size(), 3u);
    expectBinding(bindings[0], 0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                  VK_SHADER_STAGE_COMPUTE_BIT);
    expectBinding(bindings[1], 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
    expectBinding(bindings[2], 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
}

TEST(SpirvBindings, UniformBufferImagesAndBufferOfASolverStage) {
    // shaders/fluid/project.comp: the parameters uniform, its velocity component and the pressure,
    // the face buffer out, the component's image (the direct store path), the solid cells, the
    // blocks near solids, a block list and the stencils' solid corners (fluid_solids.glsl); no
    // bindings 2 and 3.
    const auto bindings =
        gpu::spirvBindings(shaders::project_comp, VK_SHADER_STAGE_COMPUTE_BIT, "project");
    ASSERT_EQ(bindings.size(), 9u);
    expectBinding(bindings[0], 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
    expectBinding(bindings[1], 1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT);
    expectBinding(bindings[2], 4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT);
    expectBinding(bindings[3], 5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
    expectBinding(bindings[4], 6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT);
    expectBinding(bindings[5], 15, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
    expectBinding(bindings[6], 19, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
    expectBinding(bindings[7], 21, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
    expectBinding(bindings[8], 22, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
}

TEST(SpirvBindings, OnlyWhatTheShaderDeclares) {
    // shaders/fluid/store_half.comp reads no parameters: no binding 0.
    const auto bindings =
        gpu::spirvBindings(shaders::store_half_comp, VK_SHADER_STAGE_COMPUTE_BIT, "store_half");
    ASSERT_EQ(bindings.size(), 2u);
    expectBinding(bindings[0], 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT);
    expectBinding(bindings[1], 2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT);
}

TEST(SpirvBindings, StagesOfOneBindingAreMerged) {
    // The character's frame uniform is read by both stages; its shadow map by the fragment only.
    const auto merged = gpu::mergeBindings(
        {gpu::spirvBindings(shaders::character_vert, VK_SHADER_STAGE_VERTEX_BIT, "character"),
         gpu::spirvBindings(shaders::character_frag, VK_SHADER_STAGE_FRAGMENT_BIT, "character")},
        "character");
    ASSERT_EQ(merged.size(), 2u);
    expectBinding(merged[0], 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                  VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT);
    expectBinding(merged[1], 1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                  VK_SHADER_STAGE_FRAGMENT_BIT);
}

TEST(SpirvBindings, ABindingOfTwoKindsIsRefused) {
    const std::vector<BindingDesc> a{
        {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT}};
    const std::vector<BindingDesc> b{
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, VK_SHADER_STAGE_FRAGMENT_BIT}};
    EXPECT_THROW(gpu::mergeBindings({a, b}, "mixed"), std::logic_error);
}

TEST(SpirvBindings, EveryEmbeddedShaderReads) {
    for (const shaders::EmbeddedShader& shader : shaders::allShaders())
        EXPECT_NO_THROW(gpu::spirvBindings(shader.spirv, VK_SHADER_STAGE_ALL, shader.fileName))
            << shader.fileName;
    for (const test_shaders::EmbeddedShader& shader : test_shaders::allShaders())
        EXPECT_NO_THROW(gpu::spirvBindings(shader.spirv, VK_SHADER_STAGE_ALL, shader.fileName))
            << shader.fileName;
}

TEST(SpirvBindings, WhatIsNotSpirvIsRefused) {
    const std::vector<uint32_t> empty;
    EXPECT_THROW(gpu::spirvBindings(empty, VK_SHADER_STAGE_COMPUTE_BIT, "empty"), std::logic_error);
    const std::vector<uint32_t> text{0x6c6c6568, 0x6f77206f, 0x00646c72, 0, 0, 0};
    EXPECT_THROW(gpu::spirvBindings(text, VK_SHADER_STAGE_COMPUTE_BIT, "text"), std::logic_error);
    // A valid header followed by an instruction that claims more words than there are.
    std::vector<uint32_t> truncated(test_shaders::selftest_saxpy_comp.begin(),
                                    test_shaders::selftest_saxpy_comp.begin() + 5);
    truncated.push_back((40u << 16) | 71u);
    EXPECT_THROW(gpu::spirvBindings(truncated, VK_SHADER_STAGE_COMPUTE_BIT, "truncated"),
                 std::logic_error);
}

} // namespace
} // namespace mfx::test
