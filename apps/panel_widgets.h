// Which widget the viewer's panel gives each key of a scene file: chosen from the key's entry in
// the parameter table (core/scene/scene_params.h) alone, so that every key the scene reader
// knows has a widget, with the range the reader checks. No user interface code here: the panel
// (apps/view_panel.cpp) draws what this says, and the tests check it for every key.
#pragma once

#include "core/scene/scene_params.h"

#include <string>

namespace mfx::app {

struct PanelWidget {
    enum class Kind {
        None,      // not shown (the effect's type, which a new effect chooses)
        Slider,    // a number on a slider between min and max
        Drag,      // a number dragged, clamped to [min, max] (ranges too wide for a slider)
        IntSlider, // a whole number on a slider
        IntDrag,   // a whole number dragged, clamped
        Checkbox,  // true or false
        Combo,     // one of the key's choices
        Colour,    // a colour picker with alpha (RGBA in [0, 1])
        Vec3,      // three numbers dragged, clamped
        IntVec3,   // three whole numbers (a grid's cells)
        NameList,  // names, edited as comma-separated text
        Text,      // a name or a file
        Gradient,  // stops of a colour over life: each stop's place and colour, a preview bar
        Curve,     // stops of a value over life: each stop's place and value, a plot
    };
    Kind kind = Kind::None;
    double min = 0.0, max = 0.0; // the reader's range (Slider, Drag, Int*, Vec3, Curve values)
    bool minOpen = false;        // min itself is refused: the widget stops just above it
    bool logarithmic = false;    // a slider over decades (min > 0 and max / min >= 1000)
    std::string format;          // printf format of the value shown
};

// The widget of `p`. Objects of stops ("colour_over_life", "width_over_life") are a Gradient
// or a Curve from their value key's entry in `table` (the section's whole table).
PanelWidget widgetFor(const scene::ParamInfo& p, const std::vector<scene::ParamInfo>& table);

// The lowest value the widget offers: min, or just above it when min is refused.
double widgetLowest(const PanelWidget& w);

} // namespace mfx::app
