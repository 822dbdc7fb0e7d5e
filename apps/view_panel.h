// The viewer's parameter panel (motionfx view, `tab` shows and hides it): Dear ImGui, from
// Debian's libimgui-dev, with its GLFW and Vulkan backends, drawn over the window's picture in a
// render pass of its own after the status lines (and after a screenshot's copy, unless the panel
// is asked for in screenshots). It lists the scene's effects with show/hide, gives every key of
// the selected effect and of the scene's sections a widget (apps/panel_widgets.h) that edits the
// scene document (core/scene/scene_document.h), scrubs the timeline, plots the passes' GPU
// milliseconds over the last frames, and saves the document. Built when libimgui-dev is found.
#pragma once

#include "core/scene/scene_document.h"
#include "sim/scene_simulation.h"

#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

struct GLFWwindow;

namespace mfx::gpu {
class Context;
class Swapchain;
} // namespace mfx::gpu

namespace mfx::app {

// What the panel shows of the viewer, each frame.
struct PanelView {
    scene::SceneDocument* document = nullptr; // null: the scene has no document (a preview)
    std::vector<std::string> effects;         // the scene's effect names, in order
    std::vector<bool> shown;                  // whether each is drawn
    int frame = 0;                            // shown, from 0
    uint32_t frameCount = 1;
    bool paused = false;
    const std::deque<sim::SimulationFrameStats>* history = nullptr; // oldest first
    std::string message; // the last thing done (saved, an edit refused, ...)
};

// What the user asked of the panel this frame.
struct PanelRequests {
    std::optional<uint32_t> seek; // go to this frame (from 0)
    bool togglePause = false;
    bool edited = false;                       // the document changed: play the scene it reads now
    std::vector<std::pair<size_t, bool>> show; // effect, shown
    bool save = false;                         // to the document's file
    std::string saveAs;                        // to this file (not empty)
    std::string refused;                       // an edit the scene reader refused, and why
};

class ViewPanel {
public:
    // Takes over ImGui's global state (one panel at a time) and chains GLFW's callbacks after
    // the ones `window` has.
    static Result<std::unique_ptr<ViewPanel>> create(const gpu::Context& ctx, GLFWwindow* window,
                                                     const gpu::Swapchain& swapchain);
    ~ViewPanel();
    ViewPanel(const ViewPanel&) = delete;
    ViewPanel& operator=(const ViewPanel&) = delete;

    // After the swapchain was made again (a new size).
    void resize(const gpu::Swapchain& swapchain);

    // Lays the panel out for this frame (nothing when hidden) and says what the user did.
    PanelRequests build(const PanelView& view);
    // Records the panel's drawing over swapchain image `index` (in colour-attachment layout,
    // left so); nothing when hidden.
    void record(VkCommandBuffer cmd, uint32_t index);

    bool visible() const { return visible_; }
    void setVisible(bool visible) { visible_ = visible; }
    // Whether the mouse is over the panel, or a text field takes the keys: the viewer's own
    // camera and keys then leave them to it.
    bool wantsMouse() const;
    bool typing() const;

private:
    ViewPanel(const gpu::Context& ctx) : ctx_(ctx) {}
    void makeFramebuffers(const gpu::Swapchain& swapchain);
    void destroyFramebuffers();

    const gpu::Context& ctx_;
    VkRenderPass renderPass_ = VK_NULL_HANDLE;
    VkDescriptorPool descriptors_ = VK_NULL_HANDLE;
    std::vector<VkFramebuffer> framebuffers_;
    VkExtent2D extent_{};
    bool backendsUp_ = false, vulkanUp_ = false;
    bool visible_ = true;
    bool built_ = false; // build() laid out a frame that record() has not drawn
    int selected_ = 0;   // the effect whose keys are shown
    char saveAs_[512] = {};
};

} // namespace mfx::app
