// motionfx view: a window playing a scene in real time, drawn by the same passes as `motionfx
// render` (render/frame_renderer.h) and copied to a swapchain, with status lines drawn on top
// (frame, frame time, state, camera, effects), keys to pause, step, scrub, restart and toggle
// effects, a mouse-driven orbit camera (apps/view_input.h), and the scene read again whenever its
// files change (apps/file_watch.h, ViewSession::reload). Needs an X server (under CI: Xvfb);
// built only when GLFW is found.
#include "apps/commands.h"

#ifdef MFX_HAVE_GLFW

#include "apps/file_watch.h"
#include "apps/view_input.h"
#include "apps/view_session.h"
#include "core/gpu/check.h"
#include "core/gpu/commands.h"
#include "core/gpu/resources.h"
#include "core/gpu/swapchain.h"
#include "render/frame_renderer.h"
#include "render/image_output.h"
#include "render/scene_player.h"
#include "render/text_overlay.h"
#include "sim/scene_simulation.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <deque>

namespace mfx::app {

namespace {

std::string glfwProblem;

void onGlfwError(int, const char* description) {
    glfwProblem = description ? description : "unknown GLFW error";
}

void say(const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
}

std::string formatMs(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", ms);
    return text;
}

// The camera's status line: where it looks from, about its target, or that it is the scene's.
std::string cameraStatus(const ViewSession& view) {
    const render::OrbitCamera orbit = render::OrbitCamera::from(view.camera());
    char text[96];
    std::snprintf(text, sizeof text, "CAMERA YAW %.0f PITCH %.0f DIST %.2f%s",
                  double(glm::degrees(orbit.yaw())), double(glm::degrees(orbit.pitch())),
                  double(orbit.distance()), view.cameraMoved() ? "" : " (SCENE)");
    return text;
}

} // namespace

int runView(const cli::ParsedArgs& parsed) {
    SceneArgument argument;
    int exitCode = kExitOk;
    if (!loadSceneArgument(parsed, argument, exitCode, "960x540")) return exitCode;
    const Result<uint32_t> samples = parseSamples(parsed);
    auto quitAfter =
        cli::parseUnsigned(parsed.value("quit-after", "0"), 0, 100000000, "--quit-after");
    if (reportFirstError(samples, quitAfter)) return kExitUsage;
    const std::string screenshot = parsed.value("screenshot");
    if (!screenshot.empty()) {
        std::ofstream probe;
        if (!openOutputFile(screenshot, probe)) return kExitFailure;
    }

    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit()) {
        printError("cannot open a window: " + glfwProblem +
                   " (motionfx view needs an X server; without a screen, run it under "
                   "xvfb-run)");
        return kExitFailure;
    }
    struct GlfwSession {
        ~GlfwSession() { glfwTerminate(); }
    } session;
    if (!glfwVulkanSupported()) {
        printError("cannot open a window: GLFW finds no Vulkan loader with window surfaces");
        return kExitFailure;
    }
    uint32_t extensionCount = 0;
    const char** extensions = glfwGetRequiredInstanceExtensions(&extensionCount);
    if (!extensions) {
        printError("cannot open a window: " + glfwProblem);
        return kExitFailure;
    }
    gpu::ContextOptions contextOpts = contextOptions(parsed);
    contextOpts.instanceExtensions.assign(extensions, extensions + extensionCount);
    contextOpts.deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    auto createdContext = gpu::Context::create(contextOpts);
    if (!createdContext) {
        printError(createdContext.error().message);
        return kExitFailure;
    }
    const gpu::Context& ctx = *createdContext.value();
    const scene::Scene& s = argument.scene;
    if (!checkOutputSize(ctx, s)) return kExitUsage;

    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    const std::string title = "motionfx view - " + s.file;
    GLFWwindow* window = glfwCreateWindow(int(s.output.width), int(s.output.height), title.c_str(),
                                          nullptr, nullptr);
    if (!window) {
        printError("cannot open a window: " + glfwProblem);
        return kExitFailure;
    }
    struct WindowOwner {
        GLFWwindow* w;
        ~WindowOwner() { glfwDestroyWindow(w); }
    } windowOwner{window};
    ViewControls controls(window);
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    if (glfwCreateWindowSurface(ctx.instance(), window, nullptr, &surface) != VK_SUCCESS) {
        printError("cannot make a Vulkan surface for the window: " + glfwProblem);
        return kExitFailure;
    }
    auto swapchainResult = gpu::Swapchain::create(ctx, surface, s.output.width, s.output.height);
    if (!swapchainResult) {
        printError(swapchainResult.error().message);
        return kExitFailure;
    }
    gpu::Swapchain& swapchain = *swapchainResult.value();

    const std::string viewedFile = s.file;
    ViewSession viewer(ctx, parsed, "960x540", std::move(argument),
                       VkSampleCountFlagBits(samples.value()));
    if (Status started = viewer.start(); !started) {
        printError(started.error().message);
        return kExitFailure;
    }
    std::printf("viewing %s on %s at %ux%u, %u frames at %g fps\n%s\n", viewedFile.c_str(),
                ctx.info().name.c_str(), viewer.scene().output.width, viewer.scene().output.height,
                viewer.frameCount(), double(viewer.scene().output.fps), kViewKeysHelp);
    FileWatch watch;
    watch.watch(viewer.files());
    if (!watch.files().empty()) {
        std::string names;
        for (const auto& file : watch.files())
            names += (names.empty() ? "" : " and ") + file.string();
        std::printf("watching %s: a saved change is played at once\n", names.c_str());
    }
    std::fflush(stdout);

    gpu::CommandBuffer commands = gpu::CommandBuffer::create(ctx, ctx.graphicsQueue());
    // A screenshot's pixels: the swapchain image copied out on the last frame.
    gpu::Buffer readback;
    bool paused = parsed.has("paused");
    uint32_t presented = 0;
    std::deque<double> recentMs; // the last frames' times, for a steady on-screen figure
    std::vector<double> allMs;
    auto lastAdvance = std::chrono::steady_clock::now();
    bool resized = false;
    bool lastFrame = false;
    bool shotWanted = false; // a screenshot asked for and not yet taken
    const std::string shotFile = screenshot.empty() ? "motionfx_view.png" : screenshot;
    std::string reloadError; // the last reload's error, shown until a reload succeeds
    float pictureHeight = float(viewer.scene().output.height); // on screen, for the pan
    while (!lastFrame) {
        glfwPollEvents();
        lastFrame = glfwWindowShouldClose(window) ||
                    (quitAfter.value() > 0 && presented + 1 >= quitAfter.value());
        const ViewInput input = controls.take();
        // Keys, each answered with a line on stdout as well as on screen.
        if (input.togglePause) {
            paused = !paused;
            say(std::string(paused ? "paused" : "playing") + " at frame " +
                std::to_string(viewer.shown() + 1));
        }
        const std::vector<scene::EffectSpec>& effects = viewer.scene().effects;
        for (int e : input.toggles)
            if (size_t(e) < effects.size()) {
                const bool show = !viewer.renderer().shown(size_t(e));
                viewer.renderer().setShown(size_t(e), show);
                say("effect " + std::to_string(e + 1) + " (" + effects[size_t(e)].name + ") " +
                    (show ? "shown" : "hidden"));
            }
        // The camera.
        if (input.sceneCamera) {
            viewer.useSceneCamera();
            say("the scene's camera");
        }
        if (input.frameCharacter) {
            viewer.frameCharacter();
            say("framed the character");
        }
        if (input.orbit != glm::vec2(0.0f)) viewer.orbit(input.orbit.x, input.orbit.y);
        if (input.pan != glm::vec2(0.0f)) viewer.pan(input.pan.x, input.pan.y, pictureHeight);
        if (input.zoom != 0.0f) viewer.zoom(input.zoom);
        if (input.printCamera) say(render::cameraBlock(viewer.camera()));
        bool advance = false;
        Status moved = Ok{};
        // The scene's files, saved since: read again, and on to the frame shown.
        if (watch.poll()) {
            std::vector<std::string> notes;
            if (Status reloaded = viewer.reload(&notes); reloaded) {
                for (const std::string& note : notes)
                    say(note);
                say("reloaded " + viewedFile + " at frame " + std::to_string(viewer.shown() + 2));
                reloadError.clear();
                advance = true;
                watch.watch(viewer.files());
            } else if (reloaded.error().message != reloadError) {
                reloadError = reloaded.error().message;
                say("reload failed, playing the last good scene: " + reloadError);
            }
        }
        if (input.restart) {
            moved = viewer.start();
            say("restarted");
        } else if (input.step != 0) {
            paused = true;
            const int target =
                std::clamp(viewer.shown() + input.step, 0, int(viewer.frameCount()) - 1);
            if (target != viewer.shown()) {
                moved = viewer.seek(uint32_t(target)); // then drawn by advancing to it
                advance = true;
            }
            say("paused at frame " + std::to_string(target + 1));
        } else if (!paused) {
            // Real time: the next frame once its time has come (every loop when slower).
            const auto now = std::chrono::steady_clock::now();
            if (std::chrono::duration<double>(now - lastAdvance).count() >=
                    1.0 / double(viewer.fps()) ||
                viewer.shown() < 0) {
                lastAdvance = now;
                advance = true;
                if (viewer.shown() + 1 >= int(viewer.frameCount())) moved = viewer.start();
            }
        }
        if (!moved) {
            printError(moved.error().message);
            return kExitFailure;
        }

        int width = 0, height = 0;
        glfwGetFramebufferSize(window, &width, &height);
        if (width == 0 || height == 0) { // minimised
            glfwWaitEventsTimeout(0.1);
            continue;
        }
        if (resized) {
            swapchain.recreate(uint32_t(width), uint32_t(height));
            resized = false;
        }
        uint32_t index = 0;
        VkSemaphore ready = VK_NULL_HANDLE;
        if (!swapchain.acquire(index, ready)) {
            swapchain.recreate(uint32_t(width), uint32_t(height));
            continue;
        }
        shotWanted = shotWanted || input.screenshot || (lastFrame && !screenshot.empty());
        const bool capture = shotWanted && swapchain.readable();
        const VkExtent2D extent = swapchain.extent();
        const auto start = std::chrono::steady_clock::now();
        VkCommandBuffer cmd = commands.begin();
        viewer.record(cmd, advance || viewer.shown() < 0);
        render::RenderTarget& target = viewer.renderer().output();
        gpu::transitionImage(cmd, target.color, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        const VkImage image = swapchain.image(index);
        gpu::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED,
                          VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        // The picture scaled to the window, letterboxed to keep its shape.
        const float scale = std::min(float(extent.width) / float(target.width),
                                     float(extent.height) / float(target.height));
        const int32_t w = std::max(1, int32_t(float(target.width) * scale));
        const int32_t h = std::max(1, int32_t(float(target.height) * scale));
        const int32_t x0 = (int32_t(extent.width) - w) / 2, y0 = (int32_t(extent.height) - h) / 2;
        pictureHeight = float(h);
        VkClearColorValue black{{0.0f, 0.0f, 0.0f, 1.0f}};
        VkImageSubresourceRange whole{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &whole);
        gpu::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkImageBlit blit{};
        blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        blit.srcOffsets[1] = {int32_t(target.width), int32_t(target.height), 1};
        blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        blit.dstOffsets[0] = {x0, y0, 0};
        blit.dstOffsets[1] = {x0 + w, y0 + h, 1};
        vkCmdBlitImage(cmd, target.color.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
        gpu::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                          VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                          VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
        // The status lines.
        VkRenderingAttachmentInfo colour{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        colour.imageView = swapchain.view(index);
        colour.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
        colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
        rendering.renderArea = {{0, 0}, extent};
        rendering.layerCount = 1;
        rendering.colorAttachmentCount = 1;
        rendering.pColorAttachments = &colour;
        vkCmdBeginRendering(cmd, &rendering);
        double shownMs = 0.0;
        for (double ms : recentMs)
            shownMs += ms / double(recentMs.size());
        const uint32_t textScale = extent.height >= 400 ? 2 : 1;
        const std::string status =
            "FRAME " + std::to_string(viewer.shown() + 1) + "/" +
            std::to_string(viewer.frameCount()) + "  " +
            (recentMs.empty() ? std::string("-") : formatMs(shownMs)) + " MS" +
            (recentMs.empty() ? "" : " (" + formatMs(1000.0 / shownMs) + " FPS)") +
            (paused ? "  PAUSED" : "");
        const glm::vec4 white(1.0f), shade(0.0f, 0.0f, 0.0f, 1.0f);
        const int margin = int(4 * textScale);
        const int lineHeight = int(10 * textScale);
        render::drawText(cmd, status, {margin, margin}, textScale, white, shade, extent);
        render::drawText(cmd, cameraStatus(viewer), {margin, margin + lineHeight}, textScale,
                         viewer.cameraMoved() ? white : glm::vec4(0.6f), shade, extent);
        int line = 2;
        const std::vector<scene::EffectSpec>& shownEffects = viewer.scene().effects;
        for (size_t e = 0; e < shownEffects.size() && e < 9; ++e, ++line) {
            const std::string label = std::to_string(e + 1) + " " + shownEffects[e].name + " " +
                                      (viewer.renderer().shown(e) ? "ON" : "OFF");
            render::drawText(cmd, label, {margin, margin + line * lineHeight}, textScale,
                             viewer.renderer().shown(e) ? white : glm::vec4(0.6f), shade, extent);
        }
        if (!reloadError.empty()) // at the bottom, in red, until the file is mended
            render::drawText(cmd, "RELOAD FAILED: " + reloadError,
                             {margin, int(extent.height) - margin - lineHeight}, textScale,
                             glm::vec4(1.0f, 0.25f, 0.2f, 1.0f), shade, extent);
        vkCmdEndRendering(cmd);
        if (capture) {
            const VkDeviceSize bytes = VkDeviceSize(extent.width) * extent.height * 4;
            readback = gpu::createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                         gpu::MemoryUsage::Readback, "view screenshot");
            gpu::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                              VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                              VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                              VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                              VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
            VkBufferImageCopy copy{};
            copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            copy.imageExtent = {extent.width, extent.height, 1};
            vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.get(),
                                   1, &copy);
            gpu::imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                              VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                              0, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0);
        } else {
            gpu::imageBarrier(
                cmd, image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0);
        }
        commands.end();
        const VkSemaphore finished = swapchain.renderFinished(index);
        commands.submit(ready, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, finished);
        if (!swapchain.present(index, finished)) resized = true;
        commands.wait();
        viewer.finish();
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        recentMs.push_back(ms);
        if (recentMs.size() > 10) recentMs.pop_front();
        allMs.push_back(ms);
        ++presented;
        if (presented == 1) {
            std::printf("first frame presented\n");
            std::fflush(stdout);
        }
        if (capture) {
            std::vector<uint8_t> rgba(static_cast<const uint8_t*>(readback.mapped),
                                      static_cast<const uint8_t*>(readback.mapped) +
                                          size_t(extent.width) * extent.height * 4);
            if (swapchain.format() == VK_FORMAT_B8G8R8A8_SRGB ||
                swapchain.format() == VK_FORMAT_B8G8R8A8_UNORM)
                for (size_t p = 0; p < rgba.size(); p += 4)
                    std::swap(rgba[p], rgba[p + 2]);
            shotWanted = false;
            if (Status written = render::writePng(shotFile, extent.width, extent.height, rgba);
                !written) {
                printError(written.error().message);
                if (lastFrame) return kExitFailure; // else the viewer plays on
            } else {
                say("screenshot of the window (" + std::to_string(extent.width) + "x" +
                    std::to_string(extent.height) + ") in " + shotFile);
            }
        } else if (shotWanted) {
            shotWanted = false;
            printError("no screenshot: this window's images cannot be read back");
        }
    }
    std::printf("closed after %u frames; median frame time %.1f ms (%.1f fps) on %s\n", presented,
                median(allMs), 1000.0 / std::max(median(allMs), 1e-6), ctx.info().name.c_str());
    return finishValidation(ctx, kExitOk);
}

} // namespace mfx::app

#else

namespace mfx::app {

int runView(std::span<const std::string>) {
    printError("motionfx view: this build has no window support (GLFW was not found when it was "
               "configured; install libglfw3-dev, or run ./build.sh, and build again)");
    return kExitFailure;
}

} // namespace mfx::app

#endif
