// Headless rendering: the lit test scene read back and checked against an analytic
// expectation, depth, occlusion, the geometry stage, and PNG output.
#include "core/gpu/commands.h"
#include "core/gpu/program.h"
#include "render/image_output.h"
#include "render/render_target.h"
#include "shaders/embedded.h"
#include "shaders/shared/selftest.h"
#include "test_shaders/embedded.h"
#include "tests/gpu_test.h"
#include "tests/test_scene_pass.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <set>
#include <stb_image.h>

namespace mfx::test {
namespace {

using RenderTest = GpuTest;

uint8_t encodeSrgb(float linear) {
    linear = std::clamp(linear, 0.0f, 1.0f);
    const float encoded =
        linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return static_cast<uint8_t>(std::lround(encoded * 255.0f));
}

glm::u8vec4 pixelAt(const std::vector<uint8_t>& rgba, uint32_t width, uint32_t x, uint32_t y) {
    const size_t i = (size_t(y) * width + x) * 4;
    return {rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]};
}

// A unit sphere at the origin seen from +z: the simplest picture with a known answer.
render::TestSceneView sphereView() {
    render::TestSceneView view;
    view.eye = {0.0f, 0.0f, 4.0f};
    view.target = {0.0f, 0.0f, 0.0f};
    view.objects = {{"sphere", glm::mat4(1.0f), {0.8f, 0.4f, 0.1f}}};
    return view;
}

struct Rendered {
    std::vector<uint8_t> color;
    std::vector<float> depth;
};

Rendered renderView(const gpu::Context& ctx, const render::TestSceneView& view, uint32_t width,
                    uint32_t height) {
    render::RenderTarget target = render::createRenderTarget(ctx, width, height);
    render::TestScenePass pass(ctx);
    gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) { pass.record(cmd, target, view); });
    return {render::readColor(ctx, target), render::readDepth(ctx, target)};
}

// The Blinn-Phong colour test_scene.frag computes where the ray through pixel (x, y) hits the unit
// sphere, and that point's depth; computed analytically on the CPU.
struct Expected {
    glm::vec3 linear;
    float depth;
};

Expected shadeSphereAt(const render::TestSceneView& view, uint32_t width, uint32_t height,
                       uint32_t x, uint32_t y) {
    const shared::TestSceneFrame frame = render::frameConstants(view, float(width) / float(height));
    const glm::mat4 inverse = glm::inverse(frame.viewProjection);
    // Pixel centre → NDC; row 0 is the top (y = +1) because the viewport is flipped.
    const float ndcX = (float(x) + 0.5f) / float(width) * 2.0f - 1.0f;
    const float ndcY = 1.0f - (float(y) + 0.5f) / float(height) * 2.0f;
    glm::vec4 near = inverse * glm::vec4(ndcX, ndcY, 0.0f, 1.0f);
    glm::vec4 far = inverse * glm::vec4(ndcX, ndcY, 1.0f, 1.0f);
    const glm::vec3 origin = glm::vec3(near) / near.w;
    const glm::vec3 direction = glm::normalize(glm::vec3(far) / far.w - origin);
    const float b = glm::dot(origin, direction);
    const float c = glm::dot(origin, origin) - 1.0f;
    const float t = -b - std::sqrt(b * b - c);
    const glm::vec3 hit = origin + t * direction;
    const glm::vec3 n = glm::normalize(hit);
    const glm::vec3 l = glm::normalize(view.lightDirection);
    const glm::vec3 v = glm::normalize(view.eye - hit);
    const glm::vec3 h = glm::normalize(l + v);
    const float diffuse = std::max(glm::dot(n, l), 0.0f);
    const float specular =
        diffuse > 0.0f ? std::pow(std::max(glm::dot(n, h), 0.0f), view.specularExponent) : 0.0f;
    const glm::vec3 base = view.objects[0].baseColor;
    const glm::vec3 linear =
        base * (view.ambient + (1.0f - view.ambient) * diffuse) * view.lightColor +
        view.specularStrength * specular * view.lightColor;
    const glm::vec4 clip = frame.viewProjection * glm::vec4(hit, 1.0f);
    return {linear, clip.z / clip.w};
}

TEST_F(RenderTest, LitSpherePixelMatchesAnalyticShading) {
    const render::TestSceneView view = sphereView();
    const uint32_t width = 96, height = 64;
    const Rendered image = renderView(ctx(), view, width, height);
    // A few pixels across the sphere, lit and in shade.
    const uint32_t probes[][2] = {{48, 32}, {40, 26}, {55, 38}, {48, 20}};
    for (const auto& p : probes) {
        const Expected expected = shadeSphereAt(view, width, height, p[0], p[1]);
        const glm::u8vec4 got = pixelAt(image.color, width, p[0], p[1]);
        // 3/255: the tessellated sphere's interpolated normal differs from the true one.
        for (int channel = 0; channel < 3; ++channel)
            EXPECT_NEAR(int(got[channel]), int(encodeSrgb(expected.linear[channel])), 3)
                << "pixel (" << p[0] << "," << p[1] << ") channel " << channel;
        EXPECT_EQ(got[3], 255);
        EXPECT_NEAR(image.depth[p[1] * width + p[0]], expected.depth, 2e-4)
            << "depth at (" << p[0] << "," << p[1] << ")";
    }
}

TEST_F(RenderTest, BackgroundKeepsClearColourAndFarDepth) {
    const render::TestSceneView view = sphereView();
    const uint32_t width = 96, height = 64;
    const Rendered image = renderView(ctx(), view, width, height);
    const glm::u8vec4 corner = pixelAt(image.color, width, 0, 0);
    for (int channel = 0; channel < 3; ++channel)
        EXPECT_EQ(corner[channel], encodeSrgb(view.clearColor[channel])) << "channel " << channel;
    EXPECT_EQ(image.depth[0], 1.0f);
    EXPECT_EQ(image.depth[width * height - 1], 1.0f);
}

TEST_F(RenderTest, ImageIsNotOneColour) {
    const uint32_t width = 96, height = 54;
    const Rendered image = renderView(ctx(), render::TestSceneView::standard(), width, height);
    std::set<uint32_t> colours;
    for (size_t i = 0; i < image.color.size(); i += 4)
        colours.insert(image.color[i] | image.color[i + 1] << 8 | image.color[i + 2] << 16);
    EXPECT_GT(colours.size(), 100u);
    size_t covered = 0;
    for (float d : image.depth)
        covered += d < 1.0f;
    EXPECT_GT(covered, image.depth.size() / 4) << "the scene should cover much of the frame";
    EXPECT_LT(covered, image.depth.size()) << "some background should show";
}

TEST_F(RenderTest, NearerObjectHidesFartherOne) {
    render::TestSceneView view = sphereView();
    // A small blue box between the camera and the sphere, drawn after it.
    glm::mat4 box = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 2.0f));
    box = glm::scale(box, glm::vec3(0.2f));
    view.objects.push_back({"box", box, {0.0f, 0.0f, 1.0f}});
    const uint32_t width = 64, height = 64;
    const Rendered image = renderView(ctx(), view, width, height);
    const glm::u8vec4 centre = pixelAt(image.color, width, 32, 32);
    EXPECT_EQ(centre.r, 0);
    EXPECT_EQ(centre.g, 0);
    EXPECT_GT(centre.b, 100);
    // Drawn in the other order, the depth test still keeps the box.
    std::swap(view.objects[0], view.objects[1]);
    const Rendered swapped = renderView(ctx(), view, width, height);
    EXPECT_EQ(pixelAt(swapped.color, width, 32, 32), centre);
}

TEST_F(RenderTest, GeometryStageExpandsPointsIntoQuads) {
    ASSERT_TRUE(ctx().features().geometryShader) << ctx().info().name << " lacks geometry shaders";
    gpu::GraphicsProgramDesc desc;
    desc.name = "selftest_points_to_quads";
    desc.vertex = test_shaders::selftest_points_to_quads_vert;
    desc.geometry = test_shaders::selftest_points_to_quads_geom;
    desc.fragment = test_shaders::selftest_points_to_quads_frag;
    desc.pushConstantSize = sizeof(shared::PointsToQuadsConstants);
    desc.vertexStride = sizeof(glm::vec2);
    desc.attributes = {{0, VK_FORMAT_R32G32_SFLOAT, 0}};
    desc.topology = VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
    desc.colorFormats = {render::kSceneColorFormat};
    desc.depthFormat = render::kDepthFormat;
    gpu::Program program = gpu::createGraphicsProgram(ctx(), desc);

    // Two points: left-top and right-bottom quadrant centres (NDC, +y up).
    const glm::vec2 points[] = {{-0.5f, 0.5f}, {0.5f, -0.5f}};
    gpu::Buffer vertices =
        gpu::createBuffer(ctx(), sizeof(points), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                          gpu::MemoryUsage::Upload, "points");
    gpu::uploadBuffer(ctx(), vertices, std::span<const glm::vec2>(points));

    const uint32_t size = 32;
    render::RenderTarget target = render::createRenderTarget(ctx(), size, size);
    shared::PointsToQuadsConstants constants{};
    constants.color = {1.0f, 1.0f, 1.0f, 1.0f};
    constants.halfSize = {0.25f, 0.25f};
    gpu::submitOneShot(ctx(), [&](VkCommandBuffer cmd) {
        render::beginRendering(cmd, target, {0.0f, 0.0f, 0.0f, 1.0f});
        program.bind(cmd);
        program.push(cmd, constants);
        const VkDeviceSize offset = 0;
        VkBuffer buffer = vertices.get();
        vkCmdBindVertexBuffers(cmd, 0, 1, &buffer, &offset);
        vkCmdDraw(cmd, 2, 1, 0, 0);
        render::endRendering(cmd);
    });
    const std::vector<uint8_t> rgba = render::readColor(ctx(), target);
    // Quads span 1/4 of the width around each point: pixels 4..11 (left, top) and 20..27.
    EXPECT_EQ(pixelAt(rgba, size, 8, 8).r, 255) << "top-left quad";
    EXPECT_EQ(pixelAt(rgba, size, 24, 24).r, 255) << "bottom-right quad";
    EXPECT_EQ(pixelAt(rgba, size, 24, 8).r, 0) << "no point top-right";
    EXPECT_EQ(pixelAt(rgba, size, 8, 24).r, 0) << "no point bottom-left";
    EXPECT_EQ(pixelAt(rgba, size, 2, 8).r, 0) << "left of the quad";
    size_t lit = 0;
    for (size_t i = 0; i < rgba.size(); i += 4)
        lit += rgba[i] == 255;
    EXPECT_EQ(lit, 2u * 8u * 8u) << "two 8x8-pixel quads";
}

TEST_F(RenderTest, PngRoundTripsThroughAFile) {
    const uint32_t width = 40, height = 24;
    const Rendered image = renderView(ctx(), render::TestSceneView::standard(), width, height);
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/png_round_trip";
    ASSERT_TRUE(render::ensureOutputDirectory(dir).ok());
    const std::string path = dir + "/scene.png";
    const Status written = render::writePng(path, width, height, image.color);
    ASSERT_TRUE(written.ok()) << written.error().message;
    int w = 0, h = 0, channels = 0;
    stbi_uc* loaded = stbi_load(path.c_str(), &w, &h, &channels, 4);
    ASSERT_NE(loaded, nullptr);
    EXPECT_EQ(w, int(width));
    EXPECT_EQ(h, int(height));
    EXPECT_TRUE(std::equal(image.color.begin(), image.color.end(), loaded));
    stbi_image_free(loaded);
}

TEST(ImageOutput, UnwritablePathIsAClearError) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR) + "/no/such/dir";
    std::filesystem::remove_all(dir);
    const std::vector<uint8_t> rgba(4 * 4 * 4, 0);
    const Status written = render::writePng(dir + "/x.png", 4, 4, rgba);
    ASSERT_FALSE(written.ok());
    EXPECT_NE(written.error().message.find(dir + "/x.png"), std::string::npos)
        << written.error().message;
}

TEST(ImageOutput, OutputDirectoryUnderAFileIsAClearError) {
    const std::string dir = std::string(MFX_TEST_OUTPUT_DIR);
    std::filesystem::create_directories(dir);
    const std::string file = dir + "/plain_file";
    { std::ofstream(file) << "x"; }
    const Status status = render::ensureOutputDirectory(file + "/sub");
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find("plain_file/sub"), std::string::npos)
        << status.error().message;
}

TEST(ImageOutput, MismatchedPixelDataIsRefused) {
    const std::vector<uint8_t> rgba(10, 0);
    EXPECT_FALSE(render::writePng(std::string(MFX_TEST_OUTPUT_DIR) + "/bad.png", 4, 4, rgba).ok());
}

} // namespace
} // namespace mfx::test
