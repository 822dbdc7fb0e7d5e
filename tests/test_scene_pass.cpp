#include "tests/test_scene_pass.h"

#include "core/gpu/context.h"
#include "shaders/embedded.h"
#include "test_shaders/embedded.h"

#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <stdexcept>
#include <string>

namespace mfx::render {

TestSceneMesh makeSphere(uint32_t rings, uint32_t segments) {
    TestSceneMesh mesh;
    for (uint32_t ring = 0; ring <= rings; ++ring) {
        const float theta = std::numbers::pi_v<float> * float(ring) / float(rings);
        for (uint32_t segment = 0; segment <= segments; ++segment) {
            const float phi = 2.0f * std::numbers::pi_v<float> * float(segment) / float(segments);
            const glm::vec3 p{std::sin(theta) * std::sin(phi), std::cos(theta),
                              std::sin(theta) * std::cos(phi)};
            mesh.vertices.push_back({p, p});
        }
    }
    const uint32_t stride = segments + 1;
    for (uint32_t ring = 0; ring < rings; ++ring) {
        for (uint32_t segment = 0; segment < segments; ++segment) {
            const uint32_t a = ring * stride + segment;
            const uint32_t b = a + stride;
            // Counter-clockwise seen from outside.
            mesh.indices.insert(mesh.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    }
    return mesh;
}

TestSceneMesh makeBox() {
    TestSceneMesh mesh;
    const glm::vec3 normals[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                  {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    for (const glm::vec3& n : normals) {
        // Tangents with u × v = n (v = n × u), so the corners run counter-clockwise from outside.
        const glm::vec3 u = std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        const glm::vec3 v = glm::cross(n, u);
        const uint32_t base = static_cast<uint32_t>(mesh.vertices.size());
        const glm::vec3 corners[4] = {n - u - v, n + u - v, n + u + v, n - u + v};
        for (const glm::vec3& c : corners)
            mesh.vertices.push_back({c, n});
        mesh.indices.insert(mesh.indices.end(),
                            {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    return mesh;
}

TestSceneView TestSceneView::standard() {
    TestSceneView view;
    glm::mat4 floor = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -1.05f, 0.0f));
    floor = glm::scale(floor, glm::vec3(4.0f, 0.05f, 4.0f));
    glm::mat4 box = glm::translate(glm::mat4(1.0f), glm::vec3(1.6f, -0.45f, -0.6f));
    box = glm::rotate(box, glm::radians(30.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    box = glm::scale(box, glm::vec3(0.55f));
    view.objects = {
        {"box", floor, {0.45f, 0.45f, 0.47f}},
        {"sphere", glm::mat4(1.0f), {0.95f, 0.35f, 0.08f}},
        {"box", box, {0.05f, 0.55f, 0.55f}},
    };
    return view;
}

shared::TestSceneFrame frameConstants(const TestSceneView& view, float aspect) {
    const glm::mat4 viewMatrix = glm::lookAt(view.eye, view.target, glm::vec3(0.0f, 1.0f, 0.0f));
    // Depth 0..1 (Vulkan), right-handed; the render target flips y in its viewport.
    const glm::mat4 projection =
        glm::perspectiveRH_ZO(glm::radians(view.verticalFovDegrees), aspect, 0.1f, 100.0f);
    shared::TestSceneFrame frame{};
    frame.viewProjection = projection * viewMatrix;
    frame.cameraPosition = glm::vec4(view.eye, 1.0f);
    frame.lightDirection = glm::vec4(glm::normalize(view.lightDirection), 0.0f);
    frame.lightColor = glm::vec4(view.lightColor, view.ambient);
    frame.specular = glm::vec4(view.specularStrength, view.specularExponent, 0.0f, 0.0f);
    return frame;
}

TestScenePass::TestScenePass(const gpu::Context& ctx) {
    gpu::GraphicsProgramDesc desc;
    desc.name = "test_scene";
    desc.vertex = test_shaders::test_scene_vert;
    desc.fragment = test_shaders::test_scene_frag;
    desc.pushConstantSize = sizeof(shared::TestSceneObject);
    desc.vertexStride = sizeof(TestSceneVertex);
    desc.attributes = {{0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(TestSceneVertex, position)},
                       {1, VK_FORMAT_R32G32B32_SFLOAT, offsetof(TestSceneVertex, normal)}};
    desc.cullMode = VK_CULL_MODE_BACK_BIT;
    desc.colorFormats = {kSceneColorFormat};
    desc.depthFormat = kDepthFormat;
    desc.depthTest = true;
    desc.depthWrite = true;
    program_ = gpu::createGraphicsProgram(ctx, desc);

    frame_ =
        gpu::createBuffer(ctx, sizeof(shared::TestSceneFrame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                          gpu::MemoryUsage::Upload, "test scene frame");
    sphere_ = upload(ctx, makeSphere(32, 64));
    box_ = upload(ctx, makeBox());
}

TestScenePass::GpuMesh TestScenePass::upload(const gpu::Context& ctx, const TestSceneMesh& mesh) {
    GpuMesh gpuMesh;
    gpuMesh.vertices =
        gpu::createBuffer(ctx, mesh.vertices.size() * sizeof(TestSceneVertex),
                          VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          gpu::MemoryUsage::DeviceLocal, "test scene vertices");
    gpu::uploadBuffer(ctx, gpuMesh.vertices, std::span<const TestSceneVertex>(mesh.vertices));
    gpuMesh.indices =
        gpu::createBuffer(ctx, mesh.indices.size() * sizeof(uint32_t),
                          VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          gpu::MemoryUsage::DeviceLocal, "test scene indices");
    gpu::uploadBuffer(ctx, gpuMesh.indices, std::span<const uint32_t>(mesh.indices));
    gpuMesh.indexCount = static_cast<uint32_t>(mesh.indices.size());
    return gpuMesh;
}

const TestScenePass::GpuMesh& TestScenePass::mesh(const char* name) const {
    if (std::strcmp(name, "sphere") == 0) return sphere_;
    if (std::strcmp(name, "box") == 0) return box_;
    throw std::invalid_argument(std::string("test scene: no mesh named ") + name);
}

void TestScenePass::record(VkCommandBuffer cmd, RenderTarget& target, const TestSceneView& view) {
    const shared::TestSceneFrame frame =
        frameConstants(view, float(target.width) / float(target.height));
    std::memcpy(frame_.mapped, &frame, sizeof(frame));

    beginRendering(cmd, target, view.clearColor);
    program_.bind(cmd, {gpu::bindBuffer(0, frame_)});
    for (const TestSceneObjectDraw& object : view.objects) {
        const GpuMesh& m = mesh(object.mesh);
        shared::TestSceneObject constants{};
        constants.model = object.model;
        constants.baseColor = glm::vec4(object.baseColor, 1.0f);
        program_.push(cmd, constants);
        const VkDeviceSize offset = 0;
        VkBuffer vertexBuffer = m.vertices.get();
        vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
        vkCmdBindIndexBuffer(cmd, m.indices.get(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, m.indexCount, 1, 0, 0, 0);
    }
    endRendering(cmd);
}

} // namespace mfx::render
