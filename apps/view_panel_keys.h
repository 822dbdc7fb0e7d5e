// The viewer panel's widgets for the keys of one section of the scene document (an effect, the
// camera, ...): each key drawn as apps/panel_widgets.h says, edits checked by the document,
// stops edited with a gradient bar or a curve plot. Part of apps/view_panel.cpp (Dear ImGui).
#pragma once

#include "apps/view_panel.h"

#include <string>

namespace mfx::app {

// Draws the keys of `section` of `doc` (inside a panel window); an edit goes to the document at
// once, and `out` says it was made (edited) or refused (why).
void editSection(scene::SceneDocument& doc, const std::string& section, PanelRequests& out);

} // namespace mfx::app
