// The skinning pass on the GPU against its CPU twin (anim::skinDualQuat): same palette, same
// vertices, positions and normals within 1e-5.
#include "core/anim/fighter.h"
#include "core/anim/skin_vertices.h"
#include "core/gpu/commands.h"
#include "tests/gpu_test.h"

#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

namespace mfx::test {
namespace {

using SkinVerticesTest = GpuTest;

// A chain of five joints up y, each turning about a different axis over a 2-second clip, one of
// them scaling non-uniformly; a tube of vertices weighted to up to four joints at random (with
// some zero weights and an influence stored as the negated quaternion's neighbour).
anim::Character chainCharacter() {
    anim::Character c;
    c.name = "chain";
    const int joints = 5;
    for (int j = 0; j < joints; ++j) {
        anim::Node node;
        node.name = "joint" + std::to_string(j);
        node.parent = j - 1;
        node.rest.translation = j == 0 ? glm::vec3(0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
        c.nodes.push_back(node);
    }
    anim::Skin skin;
    skin.name = "chain";
    for (int j = 0; j < joints; ++j) {
        skin.joints.push_back(j);
        skin.inverseBind.push_back(
            glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -float(j), 0.0f)));
    }
    c.skins.push_back(skin);

    anim::Clip clip;
    clip.name = "wave";
    clip.duration = 2.0f;
    const glm::vec3 axes[] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 1, 1}};
    for (int j = 0; j < joints; ++j) {
        anim::Channel ch;
        ch.node = j;
        ch.path = anim::Path::Rotation;
        for (int k = 0; k <= 4; ++k) {
            const float angle = 1.2f * std::sin(float(k) + float(j));
            const glm::quat q = glm::angleAxis(angle, glm::normalize(axes[j]));
            ch.times.push_back(0.5f * float(k));
            ch.values.push_back({q.x, q.y, q.z, q.w});
        }
        clip.channels.push_back(ch);
    }
    anim::Channel scale;
    scale.node = 2;
    scale.path = anim::Path::Scale;
    scale.times = {0.0f, 2.0f};
    scale.values = {{1, 1, 1, 0}, {1.5f, 0.7f, 1.2f, 0}};
    clip.channels.push_back(scale);
    c.clips.push_back(clip);

    anim::Mesh mesh;
    mesh.name = "tube";
    anim::Primitive p;
    p.skin = 0;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int ring = 0; ring <= 40; ++ring)
        for (int k = 0; k < 16; ++k) {
            const float a = 6.2831853f * float(k) / 16.0f;
            const float y = 4.0f * float(ring) / 40.0f;
            p.positions.push_back({0.3f * std::cos(a), y, 0.3f * std::sin(a)});
            p.normals.push_back({std::cos(a), 0.0f, std::sin(a)});
            const uint32_t base = std::min(uint32_t(y), 3u);
            glm::uvec4 j(base, std::min(base + 1, 4u), unit(rng) < 0.5f ? 4u : 0u,
                         uint32_t(unit(rng) * 4.99f));
            glm::vec4 w(unit(rng), unit(rng), unit(rng) < 0.3f ? 0.0f : unit(rng), unit(rng));
            if (ring % 5 == 0) w[0] = 0.0f; // the sign reference is then the second influence
            p.joints.push_back(j);
            p.weights.push_back(w / (w.x + w.y + w.z + w.w));
        }
    for (uint32_t ring = 0; ring < 40; ++ring)
        for (uint32_t k = 0; k < 16; ++k) {
            const uint32_t a = ring * 16 + k, b = ring * 16 + (k + 1) % 16;
            p.indices.insert(p.indices.end(), {a, b, a + 16, b, b + 16, a + 16});
        }
    mesh.primitives.push_back(p);
    c.meshes.push_back(mesh);
    return c;
}

TEST_F(SkinVerticesTest, GpuEqualsCpuAtTenTimes) {
    const anim::Character c = chainCharacter();
    ASSERT_TRUE(anim::checkInvariants(c).ok()) << anim::checkInvariants(c).error().message;
    const anim::Primitive& prim = c.meshes[0].primitives[0];
    const std::vector<shared::SkinVertexIn> vertices = anim::packVertices(prim);
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    gpu::Buffer input = gpu::createBuffer(ctx(), vertices.size() * sizeof(shared::SkinVertexIn),
                                          usage, gpu::MemoryUsage::DeviceLocal, "bind pose");
    gpu::uploadBuffer(ctx(), input, std::span<const shared::SkinVertexIn>(vertices));
    gpu::Buffer output = gpu::createBuffer(ctx(), vertices.size() * sizeof(shared::SkinVertexOut),
                                           usage, gpu::MemoryUsage::DeviceLocal, "skinned");
    gpu::Buffer palette =
        gpu::createBuffer(ctx(), 5 * sizeof(shared::SkinJoint), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          gpu::MemoryUsage::Upload, "palette");
    anim::SkinVertices pass(ctx());
    double worst = 0.0;
    for (int i = 0; i < 10; ++i) {
        const float t = 0.2f * float(i) + 0.013f;
        const anim::Pose pose = anim::samplePose(c, &c.clips[0], t);
        const auto joints = anim::dualQuatPalette(anim::jointMatrices(c, 0, pose));
        const auto packed = anim::packPalette(joints);
        std::memcpy(palette.mapped, packed.data(), packed.size() * sizeof(shared::SkinJoint));
        gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
            pass.record(cmd, palette, uint32_t(packed.size()), input, output,
                        uint32_t(vertices.size()));
        });
        const auto gpuOut = gpu::readBufferAs<shared::SkinVertexOut>(ctx(), output);
        const auto cpuOut = anim::skinPrimitive(c, prim, pose);
        ASSERT_EQ(gpuOut.size(), cpuOut.size());
        for (size_t v = 0; v < cpuOut.size(); ++v) {
            const double dp = glm::length(glm::dvec3(glm::vec3(gpuOut[v].position)) -
                                          glm::dvec3(cpuOut[v].position));
            const double dn =
                glm::length(glm::dvec3(glm::vec3(gpuOut[v].normal)) - glm::dvec3(cpuOut[v].normal));
            worst = std::max({worst, dp, dn});
            ASSERT_LE(dp, 1e-5) << "vertex " << v << " at t = " << t;
            ASSERT_LE(dn, 1e-5) << "normal " << v << " at t = " << t;
        }
        // Not a vacuous comparison: the pose moved the vertices.
        EXPECT_GT(glm::length(cpuOut.back().position - prim.positions.back()), 0.1f);
    }
    RecordProperty("worstDifference", std::to_string(worst));
}

// The built-in fighter, every primitive of both meshes, at 10 times of every clip.
TEST_F(SkinVerticesTest, FighterGpuEqualsCpuAtTenTimesOfEveryClip) {
    const anim::Character c = anim::makeFighter();
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    struct Part {
        const anim::Primitive* primitive;
        gpu::Buffer input, output;
    };
    std::vector<Part> parts;
    for (const anim::Mesh& m : c.meshes)
        for (const anim::Primitive& p : m.primitives) {
            const auto vertices = anim::packVertices(p);
            Part part{&p,
                      gpu::createBuffer(ctx(), vertices.size() * sizeof(shared::SkinVertexIn),
                                        usage, gpu::MemoryUsage::DeviceLocal, "bind pose"),
                      gpu::createBuffer(ctx(), vertices.size() * sizeof(shared::SkinVertexOut),
                                        usage, gpu::MemoryUsage::DeviceLocal, "skinned")};
            gpu::uploadBuffer(ctx(), part.input, std::span<const shared::SkinVertexIn>(vertices));
            parts.push_back(std::move(part));
        }
    const uint32_t jointCount = uint32_t(c.skins[0].joints.size());
    gpu::Buffer palette =
        gpu::createBuffer(ctx(), jointCount * sizeof(shared::SkinJoint),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::Upload, "palette");
    anim::SkinVertices pass(ctx());
    double worst = 0.0;
    size_t compared = 0;
    for (const anim::Clip& clip : c.clips)
        for (int i = 0; i < 10; ++i) {
            const float t = clip.duration * (float(i) + 0.5f) / 10.0f;
            const anim::Pose pose = anim::samplePose(c, &clip, t);
            const auto packed =
                anim::packPalette(anim::dualQuatPalette(anim::jointMatrices(c, 0, pose)));
            std::memcpy(palette.mapped, packed.data(), packed.size() * sizeof(shared::SkinJoint));
            gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
                for (const Part& part : parts)
                    pass.record(cmd, palette, jointCount, part.input, part.output,
                                uint32_t(part.primitive->positions.size()));
            });
            for (const Part& part : parts) {
                const auto gpuOut = gpu::readBufferAs<shared::SkinVertexOut>(ctx(), part.output);
                const auto cpuOut = anim::skinPrimitive(c, *part.primitive, pose);
                for (size_t v = 0; v < cpuOut.size(); ++v) {
                    const double dp = glm::length(glm::dvec3(glm::vec3(gpuOut[v].position)) -
                                                  glm::dvec3(cpuOut[v].position));
                    const double dn = glm::length(glm::dvec3(glm::vec3(gpuOut[v].normal)) -
                                                  glm::dvec3(cpuOut[v].normal));
                    worst = std::max({worst, dp, dn});
                    ASSERT_LE(dp, 1e-5) << clip.name << " t=" << t << " vertex " << v;
                    ASSERT_LE(dn, 1e-5) << clip.name << " t=" << t << " normal " << v;
                    ++compared;
                }
            }
        }
    RecordProperty("worstDifference", std::to_string(worst));
    EXPECT_GT(compared, 0u);
}

TEST_F(SkinVerticesTest, OutOfRangeJointsAreDroppedNotRead) {
    anim::Primitive p;
    p.positions = {{1, 2, 3}, {4, 5, 6}};
    p.normals = {{0, 0, 1}, {0, 1, 0}};
    p.joints = {{0, 99, 0, 0}, {99, 98, 97, 96}};
    p.weights = {{0.5f, 0.5f, 0, 0}, {0.25f, 0.25f, 0.25f, 0.25f}};
    const auto vertices = anim::packVertices(p);
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                     VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    gpu::Buffer input = gpu::createBuffer(ctx(), sizeof(shared::SkinVertexIn) * 2, usage,
                                          gpu::MemoryUsage::DeviceLocal, "in");
    gpu::uploadBuffer(ctx(), input, std::span<const shared::SkinVertexIn>(vertices));
    gpu::Buffer output = gpu::createBuffer(ctx(), sizeof(shared::SkinVertexOut) * 2, usage,
                                           gpu::MemoryUsage::DeviceLocal, "out");
    const auto packed = anim::packPalette(
        anim::dualQuatPalette({glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0))}));
    gpu::Buffer palette =
        gpu::createBuffer(ctx(), sizeof(shared::SkinJoint), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                          gpu::MemoryUsage::Upload, "palette");
    std::memcpy(palette.mapped, packed.data(), sizeof(shared::SkinJoint));
    anim::SkinVertices pass(ctx());
    gpu::submitOneShot(
        ctx(), [&](VkCommandBuffer cmd) { pass.record(cmd, palette, 1, input, output, 2); });
    const auto out = gpu::readBufferAs<shared::SkinVertexOut>(ctx(), output);
    // The first vertex keeps its valid influence (weights need not sum to 1 after the drop: the
    // blend is normalised), the second has none and stays put.
    EXPECT_NEAR(out[0].position.x, 11.0f, 1e-5f);
    EXPECT_NEAR(out[1].position.x, 4.0f, 1e-6f);
    EXPECT_NEAR(out[1].position.y, 5.0f, 1e-6f);
}

} // namespace
} // namespace mfx::test
