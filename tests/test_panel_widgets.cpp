// The viewer panel's widgets (apps/panel_widgets.h) come from the scene reader's parameter table:
// every key of every effect kind and scene section gets a widget of its type, with exactly the
// range the reader checks, and the lowest value a widget offers is one the reader accepts.
#include "apps/panel_widgets.h"
#include "core/scene/effect_kinds.h"
#include "core/scene/scene.h"
#include "tests/scene_params_util.h"

#include <gtest/gtest.h>

#include <set>

namespace mfx::test {
namespace {

using app::PanelWidget;
using nlohmann::json;
using scene::ParamInfo;

// The widget kinds that fit a key of type `t`.
std::set<PanelWidget::Kind> kindsFor(ParamInfo::Type t) {
    using K = PanelWidget::Kind;
    using T = ParamInfo::Type;
    switch (t) {
    case T::Number:
        return {K::Slider, K::Drag};
    case T::Integer:
        return {K::IntSlider, K::IntDrag};
    case T::Boolean:
        return {K::Checkbox};
    case T::Choice:
        return {K::Combo};
    case T::Colour:
        return {K::Colour};
    case T::Vec3:
        return {K::Vec3};
    case T::Numbers:
        return {K::IntVec3};
    case T::Strings:
        return {K::NameList};
    case T::String:
        return {K::Text};
    case T::CharacterName:
        return {K::Combo};
    case T::Objects:
        return {K::Gradient, K::Curve};
    }
    return {};
}

void checkTable(const std::vector<ParamInfo>& table, const std::string& label, const json& context,
                bool effect) {
    for (const ParamInfo& p : table) {
        if (p.key.find("[].") != std::string::npos) continue; // drawn by their array's widget
        SCOPED_TRACE(label + "." + p.key);
        const PanelWidget w = app::widgetFor(p, table);
        if (p.key == "type") {
            EXPECT_EQ(w.kind, PanelWidget::Kind::None) << "the type is chosen with a new effect";
            continue;
        }
        EXPECT_TRUE(kindsFor(p.type).count(w.kind)) << "no widget of the key's type";
        if (p.type == ParamInfo::Type::Number || p.type == ParamInfo::Type::Integer ||
            p.type == ParamInfo::Type::Vec3 || p.type == ParamInfo::Type::Numbers) {
            EXPECT_EQ(w.min, p.low);
            EXPECT_EQ(w.max, p.high);
            EXPECT_EQ(w.minOpen, p.lowOpen);
        }
        if (p.type == ParamInfo::Type::Number && effect) {
            // The widget's lowest and highest values are read by the scene reader.
            for (double v : {app::widgetLowest(w), w.max}) {
                json e = context;
                e[p.key] = v;
                const json doc = {{"effects", json::array({e})}};
                const Result<scene::Scene> read = scene::parseScene(doc.dump(), "w.json");
                EXPECT_TRUE(read.ok() || p.key == "end")
                    << v << ": " << (read.ok() ? "" : read.error().message);
            }
        }
    }
}

TEST(PanelWidgets, EveryKeyOfEveryEffectKindHasAWidgetWithTheReadersRange) {
    for (const scene::EffectKindEntry& kind : scene::effectKinds()) {
        std::set<std::string> covered;
        for (json context : choiceContexts(kind.type)) {
            context["type"] = kind.type;
            const std::vector<ParamInfo> table = scene::effectParams(kind.type, context);
            checkTable(table, kind.type, context, true);
            for (const ParamInfo& p : table)
                covered.insert(p.key.substr(0, p.key.find("[]")));
        }
        for (const std::string& key : kind.keys)
            EXPECT_TRUE(covered.count(key)) << kind.type << "." << key << " has no widget";
    }
}

TEST(PanelWidgets, EveryKeyOfEverySectionHasAWidgetWithTheReadersRange) {
    for (const std::string& section : scene::sceneSections())
        checkTable(scene::sectionParams(section), section, json::object(), false);
}

TEST(PanelWidgets, StopsAreAGradientOrACurve) {
    const std::vector<ParamInfo> lines = scene::effectParams("speed_lines");
    EXPECT_EQ(app::widgetFor(*scene::findParam(lines, "colour_over_life"), lines).kind,
              PanelWidget::Kind::Gradient);
    const PanelWidget width = app::widgetFor(*scene::findParam(lines, "width_over_life"), lines);
    EXPECT_EQ(width.kind, PanelWidget::Kind::Curve);
    EXPECT_EQ(width.max, scene::findParam(lines, "width_over_life[].width")->high);
}

} // namespace
} // namespace mfx::test
