// Compute path of the GPU layer: dispatch, push constants, specialization, storage buffers and
// 3D storage images, readback, timestamps.
#include "core/gpu/commands.h"
#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/gpu/timer.h"
#include "shaders/embedded.h"
#include "shaders/shared/selftest.h"
#include "tests/gpu_test.h"

#include <bit>
#include <vector>

namespace mfx::test {
namespace {

using ComputeTest = GpuTest;

gpu::Program makeSaxpy(const gpu::Context& ctx) {
    gpu::ComputeProgramDesc desc;
    desc.name = "selftest_saxpy";
    desc.spirv = shaders::selftest_saxpy_comp;
    desc.bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                     {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
    desc.pushConstantSize = sizeof(shared::SaxpyConstants);
    return gpu::createComputeProgram(ctx, desc);
}

// Runs saxpy on x = i, y = 3 - i: every intermediate is an integer below 2^24, so float results
// are exact whatever the device's rounding or fusing.
// The buffers hold `bufferCount` >= `count` elements; those past `count` must stay untouched.
void runSaxpy(const gpu::Context& ctx, uint32_t bufferCount, uint32_t count, float a,
              uint32_t iterations, std::vector<float>& result, gpu::GpuTimer* timer = nullptr) {
    std::vector<float> x(bufferCount), y(bufferCount);
    for (uint32_t i = 0; i < bufferCount; ++i) {
        x[i] = float(i % 4096);
        y[i] = 3.0f - float(i % 1000);
    }
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    gpu::Buffer xBuffer = gpu::createBuffer(ctx, bufferCount * sizeof(float), usage,
                                            gpu::MemoryUsage::DeviceLocal, "x");
    gpu::Buffer yBuffer = gpu::createBuffer(ctx, bufferCount * sizeof(float), usage,
                                            gpu::MemoryUsage::DeviceLocal, "y");
    gpu::uploadBuffer(ctx, xBuffer, std::span<const float>(x));
    gpu::uploadBuffer(ctx, yBuffer, std::span<const float>(y));

    gpu::Program saxpy = makeSaxpy(ctx);
    VkDescriptorSet set =
        saxpy.createSet(ctx, {gpu::bindBuffer(0, xBuffer), gpu::bindBuffer(1, yBuffer)});
    const shared::SaxpyConstants constants{a, count, iterations, 0};
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        if (timer) timer->reset(cmd);
        saxpy.bind(cmd, set);
        saxpy.push(cmd, constants);
        if (timer) timer->begin(cmd, "saxpy");
        vkCmdDispatch(cmd, gpu::groupCount(count, MFX_SAXPY_GROUP_SIZE), 1, 1);
        if (timer) timer->end(cmd);
    });
    result = gpu::readBufferAs<float>(ctx, yBuffer);
}

TEST_F(ComputeTest, SaxpyMatchesCpuElementByElement) {
    const uint32_t count = 100003; // not a multiple of the workgroup size
    const uint32_t bufferCount =
        count + 61; // the last workgroup's extra invocations must not write
    const float a = 2.0f;
    const uint32_t iterations = 3;
    std::vector<float> result;
    runSaxpy(ctx(), bufferCount, count, a, iterations, result);
    ASSERT_EQ(result.size(), bufferCount);
    uint32_t mismatches = 0;
    for (uint32_t i = 0; i < bufferCount; ++i) {
        float expected = 3.0f - float(i % 1000);
        if (i < count)
            for (uint32_t k = 0; k < iterations; ++k)
                expected = a * float(i % 4096) + expected;
        if (result[i] != expected && mismatches++ < 5)
            ADD_FAILURE() << "y[" << i << "] = " << result[i] << ", expected " << expected;
    }
    EXPECT_EQ(mismatches, 0u);
}

TEST_F(ComputeTest, TimestampsGivePositiveDurationForNontrivialDispatch) {
    ASSERT_TRUE(ctx().features().timestamps) << ctx().info().name << " reports no timestamps";
    gpu::GpuTimer timer(ctx(), 2);
    std::vector<float> result;
    runSaxpy(ctx(), 1 << 20, 1 << 20, 1.0f, 64, result, &timer);
    const std::vector<gpu::PassTime> times = timer.results();
    ASSERT_EQ(times.size(), 1u);
    EXPECT_EQ(times[0].name, "saxpy");
    EXPECT_GT(times[0].milliseconds, 0.0);
    EXPECT_LT(times[0].milliseconds, 60000.0); // a garbage tick count would be far larger
}

TEST_F(ComputeTest, FillsA3DStorageImageWithSpecializedPattern) {
    const uint32_t w = 13, h = 7, d = 3; // odd sizes: partial workgroups on every axis
    gpu::ImageDesc desc;
    desc.extent = {w, h, d};
    desc.format = VK_FORMAT_R32_SFLOAT;
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    desc.debugName = "volume";
    gpu::Image volume = gpu::createImage(ctx(), desc);

    gpu::ComputeProgramDesc programDesc;
    programDesc.name = "selftest_fill_volume";
    programDesc.spirv = shaders::selftest_fill_volume_comp;
    programDesc.bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
    programDesc.pushConstantSize = sizeof(shared::FillVolumeConstants);
    const float scale = 2.0f;
    programDesc.specialization = {std::bit_cast<uint32_t>(scale)};
    gpu::Program fill = gpu::createComputeProgram(ctx(), programDesc);
    VkDescriptorSet set =
        fill.createSet(ctx(), {gpu::bindImage(0, volume, VK_IMAGE_LAYOUT_GENERAL)});

    const float offset = 3.0f;
    shared::FillVolumeConstants constants{};
    constants.size = glm::uvec4(w, h, d, 0);
    constants.offset = offset;
    gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
        gpu::transitionImage(cmd, volume, VK_IMAGE_LAYOUT_GENERAL);
        fill.bind(cmd, set);
        fill.push(cmd, constants);
        const uint32_t g = MFX_FILL_VOLUME_GROUP_SIZE;
        vkCmdDispatch(cmd, gpu::groupCount(w, g), gpu::groupCount(h, g), gpu::groupCount(d, g));
    });
    const std::vector<std::byte> bytes = gpu::readImage(ctx(), volume);
    ASSERT_EQ(bytes.size(), size_t(w) * h * d * sizeof(float));
    const float* texels = reinterpret_cast<const float*>(bytes.data());
    uint32_t mismatches = 0;
    for (uint32_t z = 0; z < d; ++z)
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                const float expected =
                    (float(x) + 1000.0f * float(y) + 1000000.0f * float(z)) * scale + offset;
                const float got = texels[x + w * (y + h * z)];
                if (got != expected && mismatches++ < 5)
                    ADD_FAILURE() << "volume(" << x << "," << y << "," << z << ") = " << got
                                  << ", expected " << expected;
            }
    EXPECT_EQ(mismatches, 0u);
}

TEST_F(ComputeTest, ImageUploadAndReadbackRoundTrip) {
    gpu::ImageDesc desc;
    desc.extent = {5, 3, 1};
    desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    desc.usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                 VK_IMAGE_USAGE_SAMPLED_BIT;
    gpu::Image image = gpu::createImage(ctx(), desc);
    std::vector<std::byte> texels(5 * 3 * 4);
    for (size_t i = 0; i < texels.size(); ++i)
        texels[i] = std::byte(i * 7 + 1);
    gpu::uploadImage(ctx(), image, texels, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(image.layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(gpu::readImage(ctx(), image), texels);
    EXPECT_EQ(image.layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

TEST_F(ComputeTest, ReusableCommandBufferRunsTwice) {
    gpu::Buffer buffer = gpu::createBuffer(ctx(), 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                           gpu::MemoryUsage::Readback, "fill target");
    gpu::CommandBuffer commands = gpu::CommandBuffer::create(ctx(), ctx().computeQueue());
    for (uint32_t value : {7u, 11u}) {
        VkCommandBuffer cmd = commands.begin();
        vkCmdFillBuffer(cmd, buffer.get(), 0, VK_WHOLE_SIZE, value);
        commands.end();
        commands.submit();
        commands.wait();
        const std::vector<uint32_t> words = gpu::readBufferAs<uint32_t>(ctx(), buffer);
        EXPECT_EQ(words, std::vector<uint32_t>(4, value));
    }
}

TEST_F(ComputeTest, DescriptorSetMustMatchTheBindingTable) {
    gpu::Program saxpy = makeSaxpy(ctx());
    gpu::Buffer buffer = gpu::createBuffer(ctx(), 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                           gpu::MemoryUsage::DeviceLocal);
    EXPECT_THROW(saxpy.createSet(ctx(), {gpu::bindBuffer(0, buffer)}), std::logic_error)
        << "binding 1 not written";
    EXPECT_THROW(saxpy.createSet(ctx(), {gpu::bindBuffer(0, buffer), gpu::bindBuffer(1, buffer),
                                         gpu::bindBuffer(2, buffer)}),
                 std::logic_error)
        << "binding 2 not declared";
    EXPECT_THROW(saxpy.push(VK_NULL_HANDLE, uint32_t{0}), std::logic_error)
        << "push constant size mismatch";
}

} // namespace
} // namespace mfx::test
