#include "apps/view_input.h"

#ifdef MFX_HAVE_GLFW

#include <GLFW/glfw3.h>

namespace mfx::app {

namespace {

ViewControls& controls(GLFWwindow* window) {
    return *static_cast<ViewControls*>(glfwGetWindowUserPointer(window));
}

} // namespace

ViewControls::ViewControls(GLFWwindow* window) {
    glfwSetWindowUserPointer(window, this);
    glfwSetKeyCallback(window, onKey);
    glfwSetMouseButtonCallback(window, onButton);
    glfwSetCursorPosCallback(window, onCursor);
    glfwSetScrollCallback(window, onScroll);
}

ViewInput ViewControls::take() {
    ViewInput taken = std::move(pending_);
    pending_ = ViewInput{};
    return taken;
}

void ViewControls::onKey(GLFWwindow* window, int key, int, int action, int) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    ViewControls& c = controls(window);
    if (c.panelTyping_ && c.panelTyping_()) return;
    ViewInput& in = c.pending_;
    switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q:
        glfwSetWindowShouldClose(window, GLFW_TRUE);
        break;
    case GLFW_KEY_SPACE:
        in.togglePause = true;
        break;
    case GLFW_KEY_RIGHT:
    case GLFW_KEY_PERIOD:
        in.step += 1;
        break;
    case GLFW_KEY_LEFT:
    case GLFW_KEY_COMMA:
        in.step -= 1;
        break;
    case GLFW_KEY_PAGE_DOWN:
        in.step += 10;
        break;
    case GLFW_KEY_PAGE_UP:
        in.step -= 10;
        break;
    case GLFW_KEY_HOME:
    case GLFW_KEY_R:
        in.restart = true;
        break;
    case GLFW_KEY_F:
        in.frameCharacter = true;
        break;
    case GLFW_KEY_C:
        in.sceneCamera = true;
        break;
    case GLFW_KEY_P:
        in.printCamera = true;
        break;
    case GLFW_KEY_S:
        in.screenshot = true;
        break;
    case GLFW_KEY_TAB:
        in.togglePanel = true;
        break;
    default:
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) in.toggles.push_back(key - GLFW_KEY_1);
    }
}

void ViewControls::onButton(GLFWwindow* window, int button, int action, int mods) {
    ViewControls& c = controls(window);
    if (action == GLFW_RELEASE) {
        c.drag_ = Drag::None;
        return;
    }
    if (c.panelWantsMouse_ && c.panelWantsMouse_()) return; // a click on the panel
    if (button == GLFW_MOUSE_BUTTON_LEFT)
        c.drag_ = (mods & GLFW_MOD_SHIFT) ? Drag::Pan : Drag::Orbit;
    else if (button == GLFW_MOUSE_BUTTON_MIDDLE)
        c.drag_ = Drag::Pan;
}

void ViewControls::onCursor(GLFWwindow* window, double x, double y) {
    ViewControls& c = controls(window);
    const glm::vec2 at{float(x), float(y)};
    if (c.haveCursor_) {
        const glm::vec2 moved = at - c.cursor_;
        if (c.drag_ == Drag::Orbit) c.pending_.orbit += moved;
        if (c.drag_ == Drag::Pan) c.pending_.pan += moved;
    }
    c.cursor_ = at;
    c.haveCursor_ = true;
}

void ViewControls::onScroll(GLFWwindow* window, double, double dy) {
    ViewControls& c = controls(window);
    if (c.panelWantsMouse_ && c.panelWantsMouse_()) return;
    c.pending_.zoom += float(dy);
}

} // namespace mfx::app

#endif
