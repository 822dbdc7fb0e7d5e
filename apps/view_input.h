// The viewer's keys and mouse (motionfx view): GLFW's callbacks gather what was asked for between
// two frames, and the viewer takes it once a frame. Left drag orbits the camera, a middle or
// shift + left drag pans it, the wheel zooms (render/orbit_camera.h); keys as kViewKeysHelp.
#pragma once

#include <functional>
#include <glm/glm.hpp>
#include <vector>

struct GLFWwindow;

namespace mfx::app {

// What the keys and the mouse asked for since the last frame.
struct ViewInput {
    bool togglePause = false;
    int step = 0; // frames forward (+) or back (-)
    bool restart = false;
    std::vector<int> toggles; // effect indices
    glm::vec2 orbit{0.0f};    // dragged pixels (x right, y down)
    glm::vec2 pan{0.0f};      // dragged pixels
    float zoom = 0.0f;        // wheel steps, positive closer
    bool frameCharacter = false;
    bool sceneCamera = false;
    bool printCamera = false;
    bool screenshot = false;
    bool togglePanel = false;
};

class ViewControls {
public:
    // Takes over `window`'s key, button, cursor and scroll callbacks and its user pointer; the
    // controls must outlive the window's use of them.
    explicit ViewControls(GLFWwindow* window);
    // What was asked for since the last take().
    ViewInput take();
    // The panel's say over the mouse and keys: while `wantsMouse` the camera ignores the mouse,
    // while `typing` the keys are the text field's.
    void setPanelQueries(std::function<bool()> wantsMouse, std::function<bool()> typing) {
        panelWantsMouse_ = std::move(wantsMouse);
        panelTyping_ = std::move(typing);
    }

private:
    static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
    static void onButton(GLFWwindow* window, int button, int action, int mods);
    static void onCursor(GLFWwindow* window, double x, double y);
    static void onScroll(GLFWwindow* window, double dx, double dy);

    enum class Drag { None, Orbit, Pan };
    ViewInput pending_;
    std::function<bool()> panelWantsMouse_, panelTyping_;
    Drag drag_ = Drag::None;
    bool haveCursor_ = false;
    glm::vec2 cursor_{0.0f};
};

} // namespace mfx::app
