// motionfx view: a window playing a scene in real time, drawn by the same passes as `motionfx
// render` (render/frame_renderer.h) and copied to a swapchain, with status lines drawn on top
// (frame, frame time, state, camera, effects), keys to pause, step, scrub, restart and toggle
// effects, a mouse-driven orbit camera (apps/view_input.h), and the scene read again whenever its
// files change (apps/file_watch.h, ViewSession::reload). Needs an X server (under CI: Xvfb);
// built only when GLFW is found.
#include "apps/commands.h"

#ifdef MFX_HAVE_GLFW

#include "apps/file_watch.h"
#include "apps/view_frame.h"
#include "apps/view_input.h"
#include "apps/view_panel.h"
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
#include <optional>

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

// The panel where this build has one (and the window could start it); else nothing, and `tab`
// says why.
class ViewOverlay {
public:
    explicit ViewOverlay(std::unique_ptr<ViewPanel> panel, bool inScreenshots)
        : panel_(std::move(panel)), inScreenshots_(inScreenshots) {}
    bool available() const { return panel_ != nullptr; }
    bool visible() const { return panel_ && panel_->visible(); }
    void toggle() {
        if (panel_) panel_->setVisible(!panel_->visible());
    }
    bool inScreenshots() const { return inScreenshots_ && visible(); }
    bool wantsMouse() const { return panel_ && panel_->wantsMouse(); }
    bool typing() const { return panel_ && panel_->typing(); }
    PanelRequests build(const PanelView& view) {
        return panel_ ? panel_->build(view) : PanelRequests{};
    }
    void record(VkCommandBuffer cmd, uint32_t index) {
        if (panel_) panel_->record(cmd, index);
    }
    void resize(const gpu::Swapchain& swapchain) {
        if (panel_) panel_->resize(swapchain);
    }

private:
    std::unique_ptr<ViewPanel> panel_;
    bool inScreenshots_ = false;
};

ViewOverlay makeOverlay(const gpu::Context& ctx, GLFWwindow* window,
                        const gpu::Swapchain& swapchain, const cli::ParsedArgs& parsed) {
    Result<std::unique_ptr<ViewPanel>> panel = ViewPanel::create(ctx, window, swapchain);
    if (!panel) {
        std::printf("no parameter panel: %s\n", panel.error().message.c_str());
        return ViewOverlay(nullptr, false);
    }
    panel.value()->setVisible(!parsed.has("no-panel"));
    return ViewOverlay(std::move(panel).value(), parsed.has("screenshot-panel"));
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
    // The document the panel edits: the scene file, or the built-in default's text (a character
    // preview has none).
    std::unique_ptr<scene::SceneDocument> document;
    const bool builtIn = parsed.positional.empty();
    if (builtIn || !scene::isCharacterFile(parsed.positional[0])) {
        Result<scene::SceneDocument> read =
            builtIn ? scene::SceneDocument::fromText(scene::defaultSceneJson(), s.file)
                    : scene::SceneDocument::load(parsed.positional[0]);
        if (read) document = std::make_unique<scene::SceneDocument>(std::move(read).value());
    }
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
    ViewOverlay overlay = makeOverlay(ctx, window, swapchain, parsed);
    controls.setPanelQueries([&] { return overlay.wantsMouse(); },
                             [&] { return overlay.typing(); });
    std::fflush(stdout);

    gpu::CommandBuffer commands = gpu::CommandBuffer::create(ctx, ctx.graphicsQueue());
    // A screenshot's pixels: the swapchain image copied out.
    gpu::Buffer readback;
    bool paused = parsed.has("paused");
    uint32_t presented = 0;
    std::deque<double> recentMs; // the last frames' times, for a steady on-screen figure
    std::vector<double> allMs;
    std::deque<sim::SimulationFrameStats> history; // the panel's plot
    auto lastAdvance = std::chrono::steady_clock::now();
    bool resized = false;
    bool lastFrame = false;
    bool shotWanted = false; // a screenshot asked for and not yet taken
    const std::string shotFile = screenshot.empty() ? "motionfx_view.png" : screenshot;
    std::string reloadError; // the last reload's error, shown until a reload succeeds
    std::string panelMessage;
    float pictureHeight = float(viewer.scene().output.height); // on screen, for the pan
    while (!lastFrame) {
        glfwPollEvents();
        lastFrame = glfwWindowShouldClose(window) ||
                    (quitAfter.value() > 0 && presented + 1 >= quitAfter.value());
        const ViewInput input = controls.take();
        if (input.togglePanel) {
            overlay.toggle();
            say(overlay.available() ? (overlay.visible() ? "panel shown" : "panel hidden")
                                    : "no panel in this build (Dear ImGui was not found)");
        }
        // Keys, each answered with a line on stdout as well as on screen.
        bool togglePause = input.togglePause;
        std::vector<std::pair<size_t, bool>> show;
        for (int e : input.toggles)
            if (size_t(e) < viewer.scene().effects.size())
                show.emplace_back(size_t(e), !viewer.renderer().shown(size_t(e)));
        // The panel: what it shows, and what was done with it.
        PanelView panelView;
        panelView.document = document.get();
        for (size_t e = 0; e < viewer.scene().effects.size(); ++e) {
            panelView.effects.push_back(viewer.scene().effects[e].name);
            panelView.shown.push_back(viewer.renderer().shown(e));
        }
        panelView.frame = std::max(0, viewer.shown());
        panelView.frameCount = viewer.frameCount();
        panelView.paused = paused;
        panelView.history = &history;
        panelView.message = panelMessage;
        const PanelRequests asked = overlay.build(panelView);
        togglePause = togglePause != asked.togglePause;
        show.insert(show.end(), asked.show.begin(), asked.show.end());
        if (togglePause) {
            paused = !paused;
            say(std::string(paused ? "paused" : "playing") + " at frame " +
                std::to_string(viewer.shown() + 1));
        }
        for (const auto& [e, visible] : show) {
            viewer.renderer().setShown(e, visible);
            say("effect " + std::to_string(e + 1) + " (" + viewer.scene().effects[e].name + ") " +
                (visible ? "shown" : "hidden"));
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
        // The panel's edits: the scene the document reads now, from the frame shown.
        if (!asked.refused.empty()) {
            panelMessage = "refused: " + asked.refused;
            say(panelMessage);
        }
        if (asked.edited && document) {
            if (Status replaced = viewer.replace(document->scene()); replaced) {
                advance = true;
            } else {
                panelMessage = replaced.error().message;
                say(panelMessage);
            }
        }
        if (document && (asked.save || !asked.saveAs.empty())) {
            const std::string target = asked.saveAs.empty() ? document->where() : asked.saveAs;
            if (asked.saveAs.empty() && builtIn && target == viewedFile) {
                panelMessage = "the built-in scene has no file: save it as one";
            } else if (Status saved = document->save(target); saved) {
                panelMessage = "saved " + target;
                watch.watch(viewer.files()); // what was just written is not a change
            } else {
                panelMessage = saved.error().message;
            }
            say(panelMessage);
        }
        // The scene's files, saved since: read again, and on to the frame shown.
        if (watch.poll()) {
            // With a document, the file is read once, into it, and the scene it reads played:
            // the panel and the window never show two versions of the file.
            std::vector<std::string> notes;
            std::optional<scene::SceneDocument> read;
            Status reloaded = Ok{};
            if (document && !builtIn) {
                Result<scene::SceneDocument> loaded =
                    scene::SceneDocument::load(parsed.positional[0]);
                reloaded = loaded ? viewer.replace(loaded.value().scene(), &notes)
                                  : Status(loaded.error());
                if (reloaded) read = std::move(loaded).value();
            } else {
                reloaded = viewer.reload(&notes);
            }
            if (reloaded) {
                for (const std::string& note : notes)
                    say(note);
                say("reloaded " + viewedFile + " at frame " + std::to_string(viewer.shown() + 2));
                reloadError.clear();
                advance = true;
                watch.watch(viewer.files());
                if (read) *document = std::move(*read);
            } else if (reloaded.error().message != reloadError) {
                reloadError = reloaded.error().message;
                say("reload failed, playing the last good scene: " + reloadError);
            }
        }
        if (input.restart) {
            moved = viewer.start();
            say("restarted");
        } else if (input.step != 0 || asked.seek) {
            paused = true;
            const int target =
                std::clamp(asked.seek ? int(*asked.seek) : viewer.shown() + input.step, 0,
                           int(viewer.frameCount()) - 1);
            if (target != viewer.shown()) {
                moved = viewer.seek(uint32_t(target)); // then drawn by advancing to it
                advance = true;
            }
            if (!asked.seek) say("paused at frame " + std::to_string(target + 1));
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
            overlay.resize(swapchain);
            resized = false;
        }
        uint32_t index = 0;
        VkSemaphore ready = VK_NULL_HANDLE;
        if (!swapchain.acquire(index, ready)) {
            swapchain.recreate(uint32_t(width), uint32_t(height));
            overlay.resize(swapchain);
            continue;
        }
        shotWanted = shotWanted || input.screenshot || (lastFrame && !screenshot.empty());
        const bool capture = shotWanted && swapchain.readable();
        const VkExtent2D extent = swapchain.extent();
        const auto start = std::chrono::steady_clock::now();
        VkCommandBuffer cmd = commands.begin();
        viewer.record(cmd, advance || viewer.shown() < 0);
        double shownMs = 0.0;
        for (double ms : recentMs)
            shownMs += ms / double(recentMs.size());
        std::vector<StatusLine> lines;
        lines.push_back({"FRAME " + std::to_string(viewer.shown() + 1) + "/" +
                         std::to_string(viewer.frameCount()) + "  " +
                         (recentMs.empty() ? std::string("-") : formatMs(shownMs)) + " MS" +
                         (recentMs.empty() ? "" : " (" + formatMs(1000.0 / shownMs) + " FPS)") +
                         (paused ? "  PAUSED" : "")});
        lines.push_back(
            {cameraStatus(viewer), viewer.cameraMoved() ? glm::vec4(1.0f) : glm::vec4(0.6f)});
        for (size_t e = 0; e < viewer.scene().effects.size() && e < 9; ++e) {
            const bool on = viewer.renderer().shown(e);
            lines.push_back({std::to_string(e + 1) + " " + viewer.scene().effects[e].name + " " +
                                 (on ? "ON" : "OFF"),
                             on ? glm::vec4(1.0f) : glm::vec4(0.6f)});
        }
        // The error line at the bottom, in red, until the file is mended.
        const StatusLine bottom{reloadError.empty() ? "" : "RELOAD FAILED: " + reloadError,
                                glm::vec4(1.0f, 0.25f, 0.2f, 1.0f)};
        const VkImage image = swapchain.image(index);
        pictureHeight = recordWindowPicture(cmd, viewer.renderer().output(), image,
                                            swapchain.view(index), extent, lines, bottom);
        // The screenshot has the panel only when asked to.
        if (capture && !overlay.inScreenshots()) recordCopyOut(ctx, cmd, image, extent, readback);
        overlay.record(cmd, index);
        if (capture && overlay.inScreenshots()) recordCopyOut(ctx, cmd, image, extent, readback);
        gpu::imageBarrier(
            cmd, image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
            VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
            VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0);
        commands.end();
        const VkSemaphore finished = swapchain.renderFinished(index);
        commands.submit(ready, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, finished);
        if (!swapchain.present(index, finished)) resized = true;
        commands.wait();
        history.push_back(viewer.finish());
        if (history.size() > 120) history.pop_front();
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
            shotWanted = false;
            const std::vector<uint8_t> rgba = copiedPixels(readback, extent, swapchain.format());
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
