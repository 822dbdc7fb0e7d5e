#include "apps/panel_widgets.h"

#include <algorithm>
#include <cmath>

namespace mfx::app {

using scene::ParamInfo;

namespace {

// A slider where its whole range can be swept by a hand: spans of up to a few hundred units, or
// (logarithmic) a few decades of a positive range; else a drag.
PanelWidget numberWidget(const ParamInfo& p, bool whole) {
    PanelWidget w;
    w.min = p.low;
    w.max = p.high;
    w.minOpen = p.lowOpen;
    const double span = p.high - p.low;
    const bool decades = p.low >= 0.0 && p.high / std::max(p.low, 1e-300) >= 1000.0;
    if (whole) {
        w.kind = span <= 256.0 ? PanelWidget::Kind::IntSlider : PanelWidget::Kind::IntDrag;
        w.format = "%d";
        return w;
    }
    if (span <= 200.0) {
        w.kind = PanelWidget::Kind::Slider;
        w.logarithmic = decades && p.high <= 200.0 && span > 10.0;
    } else {
        w.kind = PanelWidget::Kind::Drag;
    }
    w.format = span <= 2.0 ? "%.3f" : span <= 200.0 ? "%.2f" : "%.4g";
    return w;
}

} // namespace

PanelWidget widgetFor(const ParamInfo& p, const std::vector<ParamInfo>& table) {
    using T = ParamInfo::Type;
    PanelWidget w;
    switch (p.type) {
    case T::Number:
        return numberWidget(p, false);
    case T::Integer:
        return numberWidget(p, true);
    case T::Boolean:
        w.kind = PanelWidget::Kind::Checkbox;
        return w;
    case T::Choice:
        if (p.key == "type") return w; // None
        w.kind = PanelWidget::Kind::Combo;
        return w;
    case T::CharacterName: // the document's table lists the scene's characters
        w.kind = PanelWidget::Kind::Combo;
        return w;
    case T::Colour:
        w.kind = PanelWidget::Kind::Colour;
        w.min = 0.0;
        w.max = 1.0;
        return w;
    case T::Vec3:
        w.kind = PanelWidget::Kind::Vec3;
        w.min = p.low;
        w.max = p.high;
        w.format = "%.3f";
        return w;
    case T::Numbers:
        w.kind = PanelWidget::Kind::IntVec3;
        w.min = p.low;
        w.max = p.high;
        w.format = "%d";
        return w;
    case T::Strings:
        w.kind = PanelWidget::Kind::NameList;
        return w;
    case T::String:
        w.kind = PanelWidget::Kind::Text;
        return w;
    case T::Objects: {
        // The stops' value: a colour (a gradient) or a number (a curve, with its range).
        const std::string prefix = p.key + "[].";
        for (const ParamInfo& q : table) {
            if (q.key.rfind(prefix, 0) != 0 || q.key == prefix + "at") continue;
            if (q.type == T::Colour) {
                w.kind = PanelWidget::Kind::Gradient;
                w.min = 0.0;
                w.max = 1.0;
            } else if (q.type == T::Number) {
                w.kind = PanelWidget::Kind::Curve;
                w.min = q.low;
                w.max = q.high;
                w.minOpen = q.lowOpen;
                w.format = "%.3f";
            }
        }
        return w;
    }
    }
    return w;
}

double widgetLowest(const PanelWidget& w) {
    if (!w.minOpen) return w.min;
    return w.min + std::max(1e-6, 1e-6 * std::abs(w.max - w.min));
}

} // namespace mfx::app
