// Compute path of the GPU layer: dispatch, push constants, specialization, storage buffers and
// 3D storage images, readback, timestamps.
#include "core/gpu/commands.h"
#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "core/gpu/timer.h"
#include "shaders/embedded.h"
#include "shaders/shared/selftest.h"
#include "test_shaders/embedded.h"
#include "tests/gpu_test.h"

#include <bit>
#include <cmath>
#include <vector>

namespace mfx::test {
namespace {

using ComputeTest = GpuTest;

gpu::Program makeSaxpy(const gpu::Context& ctx) {
    gpu::ComputeProgramDesc desc;
    desc.name = "selftest_saxpy";
    desc.spirv = test_shaders::selftest_saxpy_comp;
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
    const shared::SaxpyConstants constants{a, count, iterations, 0};
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
        if (timer) timer->reset(cmd);
        saxpy.bind(cmd, {gpu::bindBuffer(0, xBuffer), gpu::bindBuffer(1, yBuffer)});
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
    programDesc.spirv = test_shaders::selftest_fill_volume_comp;
    programDesc.pushConstantSize = sizeof(shared::FillVolumeConstants);
    const float scale = 2.0f;
    programDesc.specialization = {std::bit_cast<uint32_t>(scale)};
    gpu::Program fill = gpu::createComputeProgram(ctx(), programDesc);

    const float offset = 3.0f;
    shared::FillVolumeConstants constants{};
    constants.size = glm::uvec4(w, h, d, 0);
    constants.offset = offset;
    gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
        gpu::transitionImage(cmd, volume, VK_IMAGE_LAYOUT_GENERAL);
        fill.bind(cmd, {gpu::bindImage(0, volume, VK_IMAGE_LAYOUT_GENERAL)});
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

// The CPU's trilinear interpolation of a size.x*size.y*size.z r32f volume at normalised
// coordinate `p`, with clamp-to-edge addressing (Vulkan's linear filtering rule).
float trilinear(const std::vector<float>& v, glm::ivec3 size, glm::vec3 p) {
    const glm::vec3 u = p * glm::vec3(size) - 0.5f;
    const glm::ivec3 i0 = glm::ivec3(glm::floor(u));
    const glm::vec3 f = u - glm::floor(u);
    auto at = [&](glm::ivec3 c) {
        c = glm::clamp(c, glm::ivec3(0), size - 1);
        return v[c.x + size.x * (c.y + size.y * c.z)];
    };
    float result = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::ivec3 o{corner & 1, (corner >> 1) & 1, (corner >> 2) & 1};
        const glm::vec3 w = glm::mix(1.0f - f, f, glm::vec3(o));
        result += w.x * w.y * w.z * at(i0 + o);
    }
    return result;
}

TEST_F(ComputeTest, Sampled3DImageFiltersTrilinearly) {
    const glm::ivec3 size{6, 5, 4};
    std::vector<float> values(size_t(size.x) * size.y * size.z);
    for (size_t i = 0; i < values.size(); ++i)
        values[i] = float((i * 37) % 101) / 100.0f;

    gpu::ImageDesc desc;
    desc.extent = {uint32_t(size.x), uint32_t(size.y), uint32_t(size.z)};
    desc.format = VK_FORMAT_R32_SFLOAT;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    gpu::Image volume = gpu::createImage(ctx(), desc);
    gpu::uploadImage(ctx(), volume, std::as_bytes(std::span<const float>(values)),
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    gpu::UniqueSampler sampler =
        gpu::createSampler(ctx(), VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);

    // Texel centres (exact), points between texels, and points past the edges (clamped).
    std::vector<glm::vec4> coordinates;
    for (int i = 0; i < 40; ++i) {
        const float t = float(i) / 39.0f;
        coordinates.push_back({t * 1.1f - 0.05f, 0.5f + 0.4f * std::sin(7.0f * t),
                               0.5f + 0.45f * std::cos(5.0f * t), 0.0f});
    }
    coordinates.push_back({0.5f / 6.0f, 1.5f / 5.0f, 2.5f / 4.0f, 0.0f});
    const uint32_t count = uint32_t(coordinates.size());
    gpu::Buffer coordinateBuffer =
        gpu::createBuffer(ctx(), count * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          gpu::MemoryUsage::Upload, "coordinates");
    gpu::uploadBuffer(ctx(), coordinateBuffer, std::span<const glm::vec4>(coordinates));
    gpu::Buffer results =
        gpu::createBuffer(ctx(), count * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          gpu::MemoryUsage::Readback, "results");

    gpu::ComputeProgramDesc programDesc;
    programDesc.name = "selftest_sample_volume";
    programDesc.spirv = test_shaders::selftest_sample_volume_comp;
    programDesc.pushConstantSize = sizeof(shared::SampleVolumeConstants);
    gpu::Program program = gpu::createComputeProgram(ctx(), programDesc);
    gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
        program.bind(cmd, {gpu::bindImage(0, volume, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                          sampler.get()),
                           gpu::bindBuffer(1, coordinateBuffer), gpu::bindBuffer(2, results)});
        program.push(cmd, shared::SampleVolumeConstants{count, 0, 0, 0});
        vkCmdDispatch(cmd, gpu::groupCount(count, 64), 1, 1);
    });
    const std::vector<float> sampled = gpu::readBufferAs<float>(ctx(), results);
    // Filtering weights may be quantised to subTexelPrecisionBits; values lie in [0, 1].
    const float tolerance = 3.0f / float(1u << ctx().limits().subTexelPrecisionBits);
    for (uint32_t i = 0; i < count; ++i)
        EXPECT_NEAR(sampled[i], trilinear(values, size, glm::vec3(coordinates[i])), tolerance)
            << "at (" << coordinates[i].x << ", " << coordinates[i].y << ", " << coordinates[i].z
            << ")";
    // A texel centre returns the texel itself.
    EXPECT_NEAR(sampled.back(), values[0 + 6 * (1 + 5 * 2)], 1e-6f);
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

// The checks run before any command is recorded, so a null command buffer is never touched.
TEST_F(ComputeTest, PushedResourcesMustMatchTheShadersBindings) {
    gpu::Program saxpy = makeSaxpy(ctx());
    gpu::Buffer buffer = gpu::createBuffer(ctx(), 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                           gpu::MemoryUsage::DeviceLocal);
    gpu::ImageDesc desc;
    desc.extent = {2, 2, 1};
    desc.format = VK_FORMAT_R32_SFLOAT;
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
    gpu::Image image = gpu::createImage(ctx(), desc);
    EXPECT_THROW(saxpy.bind(VK_NULL_HANDLE, {gpu::bindBuffer(0, buffer)}), std::logic_error)
        << "binding 1 not written";
    EXPECT_THROW(saxpy.bind(VK_NULL_HANDLE, {gpu::bindBuffer(0, buffer), gpu::bindBuffer(1, buffer),
                                             gpu::bindBuffer(2, buffer)}),
                 std::logic_error)
        << "binding 2 not declared";
    EXPECT_THROW(
        saxpy.bind(VK_NULL_HANDLE, {gpu::bindBuffer(0, buffer), gpu::bindBuffer(0, buffer)}),
        std::logic_error)
        << "binding 0 written twice";
    EXPECT_THROW(saxpy.bind(VK_NULL_HANDLE, {gpu::bindBuffer(0, buffer),
                                             gpu::bindImage(1, image, VK_IMAGE_LAYOUT_GENERAL)}),
                 std::logic_error)
        << "an image for a buffer binding";
    EXPECT_THROW(saxpy.push(VK_NULL_HANDLE, uint32_t{0}), std::logic_error)
        << "push constant size mismatch";
}

} // namespace
} // namespace mfx::test
