// The lit test scene: a sphere, a box and a floor, shaded Blinn-Phong with one directional light.
// It exercises the graphics path end to end (vertex buffers, uniform buffer, push constants,
// depth test, sRGB target) for the rendering tests; it is built into the tests only.
#pragma once

#include "core/gpu/program.h"
#include "core/gpu/resources.h"
#include "render/render_target.h"
#include "shaders/shared/test_scene.h"

#include <glm/glm.hpp>
#include <vector>

namespace mfx::render {

struct TestSceneVertex {
    glm::vec3 position;
    glm::vec3 normal;
};

struct TestSceneMesh {
    std::vector<TestSceneVertex> vertices;
    std::vector<uint32_t> indices;
};

// A unit sphere (radius 1) of `rings` x `segments` quads with smooth normals; its poles lie on ±y.
TestSceneMesh makeSphere(uint32_t rings, uint32_t segments);
// An axis-aligned box of half-extent 1 with flat normals.
TestSceneMesh makeBox();

struct TestSceneObjectDraw {
    const char* mesh; // "sphere" or "box" (a floor is a flat box)
    glm::mat4 model;
    glm::vec3 baseColor; // linear RGB
};

struct TestSceneView {
    glm::vec3 eye{0.0f, 1.2f, 4.0f};
    glm::vec3 target{0.0f, 0.3f, 0.0f};
    float verticalFovDegrees = 45.0f;
    glm::vec3 lightDirection = glm::normalize(glm::vec3(0.4f, 0.8f, 0.45f)); // towards the light
    glm::vec3 lightColor{1.0f, 0.97f, 0.92f};
    float ambient = 0.18f;
    float specularStrength = 0.35f;
    float specularExponent = 48.0f;
    glm::vec4 clearColor{0.03f, 0.035f, 0.05f, 1.0f}; // linear
    std::vector<TestSceneObjectDraw> objects;

    // The default picture: an orange sphere on a grey floor beside a teal box.
    static TestSceneView standard();
};

// The frame constants the view produces for a target of the given aspect ratio.
shared::TestSceneFrame frameConstants(const TestSceneView& view, float aspect);

class TestScenePass {
public:
    explicit TestScenePass(const gpu::Context& ctx);

    // Records the scene into `target`: begins rendering (clearing), draws, ends rendering.
    // `view` is copied into the pass's uniform buffer immediately, so one pass records one view
    // per submission.
    void record(VkCommandBuffer cmd, RenderTarget& target, const TestSceneView& view);

private:
    struct GpuMesh {
        gpu::Buffer vertices;
        gpu::Buffer indices;
        uint32_t indexCount = 0;
    };
    GpuMesh upload(const gpu::Context& ctx, const TestSceneMesh& mesh);
    const GpuMesh& mesh(const char* name) const;

    gpu::Program program_;
    gpu::Buffer frame_;
    GpuMesh sphere_;
    GpuMesh box_;
};

} // namespace mfx::render
