// The runtime library's frames (mfxRecordFrame, include/motionfx/motionfx.h) on a host's device:
// the effects laid over a host's picture are the program's own frame when the host's picture and
// depth are the program's (render/host_frame.h: the layer path against FrameRenderer's direct
// one), the host's images end in the layouts it named, and a host's wrong depth format, colour
// format, layout or camera is one error naming it.
#include "core/gpu/commands.h"
#include "core/gpu/context.h"
#include "motionfx/motionfx.h"
#include "render/frame_renderer.h"
#include "tests/runtime/host_device.h"
#include "tests/scene_render_util.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace mfx::test {
namespace {

constexpr uint32_t kWidth = 160, kHeight = 90;
// Frame 20 of the hero scene (0.67 s): the kick's lines and its smoke are both on screen.
constexpr uint32_t kFrame = 20;

struct Messages {
    std::vector<std::string> received;
    static void callback(MfxResult, const char* message, void* user) {
        static_cast<Messages*>(user)->received.emplace_back(message);
    }
};

std::string heroFile() {
    return std::string(MFX_SOURCE_DIR) + "/docs/scenes/hero.json";
}

// The host's device, a runtime and the hero scene's effects on it, and the program's own
// Context on the same device (the test's view of the host's images and the program's frames).
class RuntimeFrame : public ::testing::Test {
protected:
    void SetUp() override {
        std::string why;
        host_ = HostDevice::make({}, why);
        ASSERT_NE(host_, nullptr) << why;
        auto ctx = gpu::Context::adopt(adoptedDevice(*host_));
        ASSERT_TRUE(ctx) << ctx.error().message;
        ctx_ = std::move(ctx).value();

        const MfxRuntimeDesc desc = runtimeDesc(*host_, &Messages::callback, &messages_);
        ASSERT_EQ(mfxCreateRuntime(&desc, &runtime_), MFX_SUCCESS);
        const std::string file = heroFile();
        MfxEffectsDesc effectsDesc{};
        effectsDesc.structVersion = MFX_EFFECTS_DESC_VERSION;
        effectsDesc.sceneFile = file.c_str();
        ASSERT_EQ(mfxCreateEffects(runtime_, &effectsDesc, &effects_), MFX_SUCCESS);

        colour_ = image(render::kSceneColorFormat,
                        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                            VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                        "host colour");
        depth_ = image(VK_FORMAT_D32_SFLOAT,
                       VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                           VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                       "host depth");
    }
    void TearDown() override {
        mfxDestroyRuntime(runtime_);
        if (host_ != nullptr) {
            EXPECT_EQ(host_->validationErrors(), 0u);
        }
    }

    gpu::Image image(VkFormat format, VkImageUsageFlags usage, const char* name) {
        gpu::ImageDesc d;
        d.extent = {kWidth, kHeight, 1};
        d.format = format;
        d.usage = usage;
        d.debugName = name;
        return gpu::createImage(*ctx_, d);
    }

    // A frame description over the host images, from the scene's camera, at frame `frame`.
    MfxFrameDesc describe(VkCommandBuffer cmd, uint32_t frame) {
        MfxFrameDesc d{};
        d.structVersion = MFX_FRAME_DESC_VERSION;
        d.commandBuffer = cmd;
        d.time = double(frame) / 30.0;
        EXPECT_EQ(mfxGetSceneCamera(effects_, float(kWidth) / float(kHeight), &d.camera),
                  MFX_SUCCESS);
        d.width = kWidth;
        d.height = kHeight;
        d.colour = {colour_.get(), colour_.format, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
        d.depth = {depth_.get(), depth_.format, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
        d.samples = 1;
        return d;
    }

    // The refusal of one bad description: its result and the one line it sent.
    std::string refusal(const MfxFrameDesc& desc) {
        messages_.received.clear();
        EXPECT_EQ(mfxRecordFrame(effects_, &desc), MFX_ERROR_INVALID_ARGUMENT);
        EXPECT_EQ(messages_.received.size(), 1u);
        const std::string message = messages_.received.empty() ? "" : messages_.received.back();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_EQ(message, mfxRuntimeLastError(runtime_));
        return message;
    }

    std::unique_ptr<HostDevice> host_;
    std::unique_ptr<gpu::Context> ctx_;
    Messages messages_;
    MfxRuntime runtime_ = nullptr;
    MfxEffects effects_ = nullptr;
    gpu::Image colour_, depth_;
};

// Copies the program's picture (its colour and depth) into the host's images, left in
// TRANSFER_DST_OPTIMAL as describe() says.
void copyPicture(VkCommandBuffer cmd, render::RenderTarget& target, gpu::Image& colour,
                 gpu::Image& depth) {
    gpu::imageBarrier(cmd, target.color, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    gpu::imageBarrier(cmd, target.depth, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    for (gpu::Image* to : {&colour, &depth})
        gpu::imageBarrier(cmd, *to, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                          VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageCopy region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstSubresource = region.srcSubresource;
    region.extent = {kWidth, kHeight, 1};
    vkCmdCopyImage(cmd, target.color.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, colour.get(),
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    region.srcSubresource.aspectMask = region.dstSubresource.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
    vkCmdCopyImage(cmd, target.depth.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, depth.get(),
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                       VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
}

std::vector<float> halves(const std::vector<std::byte>& bytes) {
    std::vector<uint16_t> h(bytes.size() / 2);
    std::memcpy(h.data(), bytes.data(), h.size() * 2);
    std::vector<float> out(h.size());
    for (size_t i = 0; i < h.size(); ++i)
        out[i] = glm::unpackHalf1x16(h[i]);
    return out;
}

// The program draws frame kFrame of the hero scene (no bloom, no tone map: the linear picture);
// the host's images get the program's picture of the same frame without its effects; the runtime,
// which simulated the same frames, lays its effects over them. The result is the program's frame.
void expectTheProgramsFrame(gpu::Context& ctx, gpu::Image& colour, gpu::Image& depth,
                            MfxEffects effects,
                            const std::function<MfxFrameDesc(VkCommandBuffer, uint32_t)>& describe,
                            VkSampleCountFlagBits samples, float tolerance, double outsideShare) {
    auto scene = docScene("hero");
    ASSERT_TRUE(scene) << scene.error().message;
    scene.value().post.bloom = 0.0f;
    scene.value().post.toneMap = scene::ToneMap::None;
    auto drawn = drawScene(ctx, scene.value(), kWidth, kHeight, samples);
    ASSERT_TRUE(drawn) << drawn.error().message;
    render::FrameRenderer& renderer = *drawn.value().renderer;
    sim::SceneSimulation& simulation = *drawn.value().simulation;
    const size_t effectCount = simulation.scene().effects.size();

    std::vector<float> programs, under;
    for (uint32_t f = 0; f <= kFrame; ++f) {
        gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) { renderer.record(cmd, simulation, f); });
        simulation.finishFrame();
        if (f == kFrame) programs = render::readLinearColor(ctx, renderer.sceneTarget());
        // The same frame without its effects: the host's picture.
        for (size_t e = 0; e < effectCount; ++e)
            renderer.setShown(e, false);
        gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
            renderer.recordDraw(cmd, simulation, simulation.frameTime(f));
        });
        for (size_t e = 0; e < effectCount; ++e)
            renderer.setShown(e, true);
        if (f == kFrame) under = render::readLinearColor(ctx, renderer.sceneTarget());
        MfxResult result = MFX_SUCCESS;
        gpu::submitOneShot(ctx, [&](VkCommandBuffer cmd) {
            copyPicture(cmd, renderer.sceneTarget(), colour, depth);
            const MfxFrameDesc desc = describe(cmd, f);
            result = mfxRecordFrame(effects, &desc);
        });
        ASSERT_EQ(result, MFX_SUCCESS) << "frame " << f;
        colour.layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL; // where the runtime left it
    }
    const std::vector<float> hosts = halves(gpu::readImage(ctx, colour));
    ASSERT_EQ(hosts.size(), programs.size());

    // The effects are on screen: not a comparison of two empty layers.
    size_t touched = 0, outside = 0;
    float largest = 0.0f;
    for (size_t p = 0; p < programs.size(); p += 4) {
        float effect = 0.0f, difference = 0.0f;
        for (int c = 0; c < 3; ++c) {
            effect = std::max(effect, std::abs(programs[p + c] - under[p + c]));
            difference = std::max(difference, std::abs(hosts[p + c] - programs[p + c]) /
                                                  std::max(1.0f, std::abs(programs[p + c])));
        }
        if (effect > 0.05f) ++touched;
        if (difference > tolerance) ++outside;
        largest = std::max(largest, difference);
    }
    EXPECT_GT(touched, programs.size() / 4 / 50) << "the effects cover under 2% of the frame";
    EXPECT_LE(double(outside), outsideShare * double(programs.size() / 4))
        << outside << " pixels differ by more than " << tolerance << " (largest " << largest
        << "); the effects changed " << touched << " pixels";
    std::printf("%zu pixels with effects; %zu over %.4f; largest difference %.5f\n", touched,
                outside, double(tolerance), double(largest));
}

// One sample a pixel on both sides: the layer's premultiplied "over" and the program's blending
// straight into its picture differ by the fp16 rounding of the layer alone. Relative to the
// value above 1 (the additive lines are HDR): fp16 keeps 11 bits, and a pixel sums a few layers.
TEST_F(RuntimeFrame, OverTheProgramsPictureTheEffectsAreTheProgramsFrame) {
    expectTheProgramsFrame(
        *ctx_, colour_, depth_, effects_,
        [&](VkCommandBuffer cmd, uint32_t f) { return describe(cmd, f); }, VK_SAMPLE_COUNT_1_BIT,
        4e-3f, 0.0);
}

// Four samples on both sides: the program's effects are tested against the four depths of each
// pixel, the layer's against the one the host's single-sampled depth holds; pixels on the
// character's and the stage's silhouettes may differ, no others.
TEST_F(RuntimeFrame, WithFourSamplesOnlySilhouettePixelsDiffer) {
    expectTheProgramsFrame(
        *ctx_, colour_, depth_, effects_,
        [&](VkCommandBuffer cmd, uint32_t f) {
            MfxFrameDesc d = describe(cmd, f);
            d.samples = 4;
            return d;
        },
        VK_SAMPLE_COUNT_4_BIT, 4e-3f, 0.02);
}

// A projection flipped for a viewport of positive height (clipYDown 1) is the example's
// (examples/host), compared with the program's render by RuntimeExample.ItsEffectsMatch...

TEST_F(RuntimeFrame, BadTargetsAndCamerasAreOneErrorNamingTheField) {
    gpu::submitOneShot(*ctx_, [&](VkCommandBuffer cmd) {
        const MfxFrameDesc good = describe(cmd, 0);
        auto with = [&](auto change) {
            MfxFrameDesc d = good;
            change(d);
            return refusal(d);
        };
        auto contains = [](const std::string& text, const std::string& part) {
            return text.find(part) != std::string::npos;
        };
        std::string m = with([](MfxFrameDesc& d) { d.depth.format = VK_FORMAT_R8G8B8A8_UNORM; });
        EXPECT_TRUE(contains(m, "depth.format VK_FORMAT_R8G8B8A8_UNORM is not a depth format"))
            << m;
        EXPECT_TRUE(contains(m, "VK_FORMAT_D24_UNORM_S8_UINT")) << m;
        m = with([](MfxFrameDesc& d) { d.colour.format = VK_FORMAT_D32_SFLOAT; });
        EXPECT_TRUE(contains(m, "colour.format VK_FORMAT_D32_SFLOAT")) << m;
        m = with([](MfxFrameDesc& d) { d.colour.layout = VK_IMAGE_LAYOUT_UNDEFINED; });
        EXPECT_TRUE(contains(m, "colour.layout is VK_IMAGE_LAYOUT_UNDEFINED")) << m;
        m = with([](MfxFrameDesc& d) {
            d.depth.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        });
        EXPECT_TRUE(contains(m, "depth.finalLayout VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL")) << m;
        m = with([](MfxFrameDesc& d) { d.width = 0; });
        EXPECT_TRUE(contains(m, "width and height")) << m;
        m = with([](MfxFrameDesc& d) { d.depth.image = VK_NULL_HANDLE; });
        EXPECT_TRUE(contains(m, "depth.image is null")) << m;
        m = with([](MfxFrameDesc& d) { d.time = std::nan(""); });
        EXPECT_TRUE(contains(m, "MfxFrameDesc.time")) << m;
        m = with([](MfxFrameDesc& d) { d.samples = 3; });
        EXPECT_TRUE(contains(m, "MfxFrameDesc.samples")) << m;
        m = with([](MfxFrameDesc& d) { d.commandBuffer = VK_NULL_HANDLE; });
        EXPECT_TRUE(contains(m, "commandBuffer")) << m;
        m = with([](MfxFrameDesc& d) { d.structVersion = 99; });
        EXPECT_TRUE(contains(m, "structVersion is 99")) << m;
        // An orthographic projection, and one with reversed depth (near 1, far 0).
        m = with([](MfxFrameDesc& d) {
            std::fill(std::begin(d.camera.projection), std::end(d.camera.projection), 0.0f);
            d.camera.projection[0] = d.camera.projection[5] = d.camera.projection[15] = 1.0f;
            d.camera.projection[10] = -0.1f;
        });
        EXPECT_TRUE(contains(m, "camera.projection is not a right-handed perspective")) << m;
        m = with([](MfxFrameDesc& d) {
            d.camera.projection[10] = -d.camera.projection[10] - 1.0f; // A' = -A - 1
            d.camera.projection[14] = -d.camera.projection[14];        // B' = -B
        });
        EXPECT_TRUE(contains(m, "reversed or infinite depth")) << m;
        m = with([](MfxFrameDesc& d) { d.camera.view[3] = INFINITY; });
        EXPECT_TRUE(contains(m, "camera.view[3] is not a finite number")) << m;
    });
    // Nothing was recorded by the refusals: a good frame still draws, and the time cannot go back.
    MfxResult result = MFX_ERROR_INTERNAL;
    gpu::submitOneShot(*ctx_, [&](VkCommandBuffer cmd) {
        for (gpu::Image* image : {&colour_, &depth_})
            gpu::imageBarrier(cmd, *image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                              VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                              VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
        const MfxFrameDesc d = describe(cmd, 3);
        result = mfxRecordFrame(effects_, &d);
    });
    EXPECT_EQ(result, MFX_SUCCESS) << mfxRuntimeLastError(runtime_);
    gpu::submitOneShot(*ctx_, [&](VkCommandBuffer cmd) {
        MfxFrameDesc d = describe(cmd, 3);
        d.colour.layout = d.colour.finalLayout;
        // The first frame recorded is frame 0 whatever the time (the effects start there and
        // advance a frame a call): time 0 draws that frame again.
        d.time = 0.0;
        result = mfxRecordFrame(effects_, &d);
    });
    EXPECT_EQ(result, MFX_SUCCESS) << mfxRuntimeLastError(runtime_);
}

TEST_F(RuntimeFrame, TheTimeCannotGoBack) {
    for (uint32_t f : {0u, 1u, 2u}) {
        MfxResult result = MFX_ERROR_INTERNAL;
        gpu::submitOneShot(*ctx_, [&](VkCommandBuffer cmd) {
            MfxFrameDesc d = describe(cmd, f);
            d.colour.layout = f == 0 ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : d.colour.finalLayout;
            if (f == 0)
                for (gpu::Image* image : {&colour_, &depth_})
                    gpu::imageBarrier(
                        cmd, *image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT);
            result = mfxRecordFrame(effects_, &d);
        });
        ASSERT_EQ(result, MFX_SUCCESS) << mfxRuntimeLastError(runtime_);
    }
    gpu::submitOneShot(*ctx_, [&](VkCommandBuffer cmd) {
        MfxFrameDesc d = describe(cmd, 1);
        d.colour.layout = d.colour.finalLayout;
        const std::string m = refusal(d);
        EXPECT_NE(m.find("MfxFrameDesc.time 0.033333 s is before frame 2 already simulated"),
                  std::string::npos)
            << m;
    });
}

// Effects made again from another scene (the lines scene: speed-lines alone, no smoke).
MfxEffects makeEffects(MfxRuntime runtime, const std::string& scene) {
    const std::string file = std::string(MFX_SOURCE_DIR) + "/docs/scenes/" + scene + ".json";
    MfxEffectsDesc desc{};
    desc.structVersion = MFX_EFFECTS_DESC_VERSION;
    desc.sceneFile = file.c_str();
    MfxEffects effects = nullptr;
    EXPECT_EQ(mfxCreateEffects(runtime, &desc, &effects), MFX_SUCCESS)
        << mfxRuntimeLastError(runtime);
    return effects;
}

// The host animates the character: given the clip's own node matrices, the effects are the
// clip-driven ones bit for bit; given them moved 0.4 m along +x, the effects move right on
// screen (the camera looks from +x +z).
TEST_F(RuntimeFrame, TheHostsNodeMatricesDriveTheEffects) {
    MfxEffects byClip = makeEffects(runtime_, "lines"), byHost = makeEffects(runtime_, "lines"),
               moved = makeEffects(runtime_, "lines");
    ASSERT_TRUE(byClip && byHost && moved);
    const uint32_t nodes = mfxGetCharacterNodeCount(byHost);
    ASSERT_GT(nodes, 10u);
    EXPECT_NE(mfxGetCharacterNodeName(byHost, 0), nullptr);
    EXPECT_EQ(mfxGetCharacterNodeName(byHost, nodes), nullptr);
    std::vector<gpu::Image> colours;
    for (int i = 0; i < 3; ++i)
        colours.push_back(image(render::kSceneColorFormat,
                                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                "host colour"));
    std::vector<float> matrices(16 * size_t(nodes)), shifted(matrices.size());
    for (uint32_t f = 0; f <= 12; ++f) {
        ASSERT_EQ(mfxGetCharacterNodeMatrices(byHost, double(f) / 30.0, matrices.data()),
                  MFX_SUCCESS);
        for (size_t n = 0; n < nodes; ++n) {
            const glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(0.4f, 0.0f, 0.0f)) *
                                glm::make_mat4(matrices.data() + 16 * n);
            std::memcpy(shifted.data() + 16 * n, glm::value_ptr(m), sizeof(m));
        }
        std::vector<MfxResult> results;
        gpu::submitOneShot(*ctx_, [&](VkCommandBuffer cmd) {
            const VkClearColorValue grey{{0.2f, 0.2f, 0.2f, 1.0f}};
            const VkClearDepthStencilValue far{1.0f, 0};
            const VkImageSubresourceRange colourRange{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            const VkImageSubresourceRange depthRange{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
            for (gpu::Image* target : {&colours[0], &colours[1], &colours[2], &depth_}) {
                gpu::imageBarrier(cmd, *target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                  VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                  VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                                  VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
                if (target == &depth_)
                    vkCmdClearDepthStencilImage(cmd, target->get(),
                                                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &far, 1,
                                                &depthRange);
                else
                    vkCmdClearColorImage(cmd, target->get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                         &grey, 1, &colourRange);
            }
            gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                               VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                               VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
            MfxEffects all[3] = {byClip, byHost, moved};
            for (int i = 0; i < 3; ++i) {
                MfxFrameDesc d = describe(cmd, f);
                d.colour.image = colours[size_t(i)].get();
                if (i > 0) {
                    d.nodeMatrices = i == 1 ? matrices.data() : shifted.data();
                    d.nodeMatrixCount = nodes;
                }
                results.push_back(mfxRecordFrame(all[i], &d));
            }
        });
        for (MfxResult r : results)
            ASSERT_EQ(r, MFX_SUCCESS) << mfxRuntimeLastError(runtime_);
        for (gpu::Image& colour : colours)
            colour.layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    }
    std::vector<std::vector<float>> pictures;
    for (gpu::Image& colour : colours)
        pictures.push_back(halves(gpu::readImage(*ctx_, colour)));
    EXPECT_EQ(pictures[0], pictures[1]) << "the clip's matrices given by the host";
    // The effects' pixels (off the grey) and their mean column.
    auto effectColumn = [](const std::vector<float>& p, size_t& count) {
        double sum = 0.0;
        count = 0;
        for (size_t i = 0; i < p.size(); i += 4)
            if (std::abs(p[i] - 0.2f) + std::abs(p[i + 1] - 0.2f) + std::abs(p[i + 2] - 0.2f) >
                0.05f) {
                sum += double((i / 4) % kWidth);
                ++count;
            }
        return count > 0 ? sum / double(count) : 0.0;
    };
    size_t clipPixels = 0, movedPixels = 0;
    const double clipColumn = effectColumn(pictures[0], clipPixels);
    const double movedColumn = effectColumn(pictures[2], movedPixels);
    EXPECT_GT(clipPixels, 100u);
    EXPECT_GT(movedPixels, 100u);
    EXPECT_GT(movedColumn, clipColumn + 5.0) << "the effects did not follow the moved pose";
    std::printf("effects' mean column: %.1f by the clip, %.1f moved 0.4 m along +x\n", clipColumn,
                movedColumn);

    // A wrong count or a NaN is refused before anything is recorded.
    gpu::submitOneShot(*ctx_, [&](VkCommandBuffer cmd) {
        MfxFrameDesc d = describe(cmd, 13);
        d.nodeMatrices = matrices.data();
        d.nodeMatrixCount = nodes - 1;
        messages_.received.clear();
        EXPECT_EQ(mfxRecordFrame(byHost, &d), MFX_ERROR_INVALID_ARGUMENT);
        EXPECT_EQ(std::string(mfxRuntimeLastError(runtime_)),
                  "MfxFrameDesc.nodeMatrixCount is " + std::to_string(nodes - 1) +
                      "; the character has " + std::to_string(nodes) +
                      " nodes (mfxGetCharacterNodeCount)");
        d.nodeMatrixCount = nodes;
        matrices[5] = std::nanf("");
        EXPECT_EQ(mfxRecordFrame(byHost, &d), MFX_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(mfxRuntimeLastError(runtime_)).find("node 0"), std::string::npos)
            << mfxRuntimeLastError(runtime_);
    });
    for (MfxEffects e : {byClip, byHost, moved})
        mfxDestroyEffects(e);
}

TEST_F(RuntimeFrame, TheCharacterMeshIsTheScenesCharacterPosedAtTheTime) {
    uint32_t vertices = 0, indices = 0;
    ASSERT_EQ(mfxGetCharacterMeshSize(effects_, &vertices, &indices), MFX_SUCCESS);
    ASSERT_GT(vertices, 100u);
    ASSERT_EQ(indices % 3, 0u);
    std::vector<float> start(3 * size_t(vertices)), kick(3 * size_t(vertices)),
        normals(3 * size_t(vertices));
    std::vector<uint32_t> triangles(indices);
    ASSERT_EQ(mfxGetCharacterMesh(effects_, 0.0, start.data(), nullptr, triangles.data()),
              MFX_SUCCESS);
    ASSERT_EQ(mfxGetCharacterMesh(effects_, 0.6, kick.data(), normals.data(), nullptr),
              MFX_SUCCESS);
    for (uint32_t i : triangles)
        ASSERT_LT(i, vertices);
    // It moves, stands on the floor and is about a fighter's height; its normals are unit.
    float moved = 0.0f, low = 1e9f, high = -1e9f;
    for (size_t v = 0; v < vertices; ++v) {
        moved = std::max(moved, std::abs(kick[3 * v] - start[3 * v]) +
                                    std::abs(kick[3 * v + 1] - start[3 * v + 1]) +
                                    std::abs(kick[3 * v + 2] - start[3 * v + 2]));
        low = std::min(low, start[3 * v + 1]);
        high = std::max(high, start[3 * v + 1]);
        const float length =
            std::sqrt(normals[3 * v] * normals[3 * v] + normals[3 * v + 1] * normals[3 * v + 1] +
                      normals[3 * v + 2] * normals[3 * v + 2]);
        EXPECT_NEAR(length, 1.0f, 1e-3f) << "vertex " << v;
    }
    EXPECT_GT(moved, 0.3f);
    MfxEffectsInfo info{};
    info.structVersion = MFX_EFFECTS_INFO_VERSION;
    ASSERT_EQ(mfxGetEffectsInfo(effects_, &info), MFX_SUCCESS);
    // The fighter stands on the floor: its soles reach 5.7 cm into it at rest (the mesh's own
    // shape), so within 10 cm.
    EXPECT_NEAR(low, info.floorHeight, 0.1f);
    EXPECT_GT(high - low, 1.4f);
    EXPECT_LT(high - low, 2.4f);
    EXPECT_EQ(mfxGetCharacterMesh(effects_, -1.0, start.data(), nullptr, nullptr),
              MFX_ERROR_INVALID_ARGUMENT);
}

} // namespace
} // namespace mfx::test
