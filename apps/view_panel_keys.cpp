#include "apps/view_panel_keys.h"

#ifdef MFX_HAVE_IMGUI

#include "apps/panel_widgets.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mfx::app {

using nlohmann::json;
using scene::ParamInfo;

namespace {

constexpr int kMaxStops = 8;

float number(const json& v, float fallback = 0.0f) {
    return v.is_number() ? v.get<float>() : fallback;
}

// The colour of a colour stop list at u (linear between stops), for the gradient's preview.
ImVec4 colourAt(const json& stops, const std::string& key, float u) {
    auto colourOf = [&](const json& s) {
        const json& c = s.contains(key) ? s[key] : json::array({1, 1, 1, 1});
        return ImVec4(number(c[0]), number(c[1]), number(c[2]), c.size() > 3 ? number(c[3]) : 1.0f);
    };
    if (!stops.is_array() || stops.empty()) return ImVec4(1, 1, 1, 1);
    if (u <= number(stops.front()["at"])) return colourOf(stops.front());
    for (size_t i = 1; i < stops.size(); ++i) {
        const float a = number(stops[i - 1]["at"]), b = number(stops[i]["at"]);
        if (u <= b) {
            const float f = b > a ? (u - a) / (b - a) : 1.0f;
            const ImVec4 x = colourOf(stops[i - 1]), y = colourOf(stops[i]);
            return ImVec4(x.x + (y.x - x.x) * f, x.y + (y.y - x.y) * f, x.z + (y.z - x.z) * f,
                          x.w + (y.w - x.w) * f);
        }
    }
    return colourOf(stops.back());
}

// The key of the stops' value ("colour", "width", "size") in `table`.
std::string stopValueKey(const ParamInfo& p, const std::vector<ParamInfo>& table) {
    const std::string prefix = p.key + "[].";
    for (const ParamInfo& q : table)
        if (q.key.rfind(prefix, 0) == 0 && q.key != prefix + "at")
            return q.key.substr(prefix.size());
    return "value";
}

// Edits the stops `value` (an array of {"at", <key>}) of widget `w`; true when changed.
bool editStops(const ParamInfo& p, const PanelWidget& w, const std::vector<ParamInfo>& table,
               json& value) {
    const std::string key = stopValueKey(p, table);
    const bool gradient = w.kind == PanelWidget::Kind::Gradient;
    if (!value.is_array() || value.size() < 2) {
        ImGui::TextDisabled("%s: none", p.key.c_str());
        ImGui::SameLine();
        if (!ImGui::SmallButton("add")) return false;
        const json high = gradient ? json::array({1, 1, 1, 1}) : json(std::min(w.max, 1.0));
        const json low = gradient ? json::array({1, 1, 1, 0}) : json(widgetLowest(w));
        value = json::array({{{"at", 0.0}, {key, high}}, {{"at", 1.0}, {key, low}}});
        return true;
    }
    bool changed = false;
    ImGui::TextUnformatted(p.key.c_str());
    // The preview: the gradient as a bar, the curve as a plot.
    const float width = ImGui::GetContentRegionAvail().x;
    if (gradient) {
        ImDrawList* draw = ImGui::GetWindowDrawList();
        const ImVec2 at = ImGui::GetCursorScreenPos();
        constexpr int kSteps = 32;
        for (int i = 0; i < kSteps; ++i) {
            const float u0 = float(i) / kSteps, u1 = float(i + 1) / kSteps;
            const ImU32 c0 = ImGui::ColorConvertFloat4ToU32(colourAt(value, key, u0));
            const ImU32 c1 = ImGui::ColorConvertFloat4ToU32(colourAt(value, key, u1));
            draw->AddRectFilledMultiColor(ImVec2(at.x + width * u0, at.y),
                                          ImVec2(at.x + width * u1, at.y + 14.0f), c0, c1, c1, c0);
        }
        ImGui::Dummy(ImVec2(width, 16.0f));
    } else {
        float samples[32];
        for (int i = 0; i < 32; ++i) {
            const float u = float(i) / 31.0f;
            float v = number(value.front()[key]);
            for (size_t s = 1; s < value.size(); ++s) {
                const float a = number(value[s - 1]["at"]), b = number(value[s]["at"]);
                if (u >= a && u <= b) {
                    const float f = b > a ? (u - a) / (b - a) : 1.0f;
                    v = number(value[s - 1][key]) +
                        (number(value[s][key]) - number(value[s - 1][key])) * f;
                    break;
                }
                if (u > b) v = number(value[s][key]);
            }
            samples[i] = v;
        }
        ImGui::PlotLines("##curve", samples, 32, 0, nullptr, float(widgetLowest(w)),
                         float(std::max(w.max > 10.0 ? 2.0 : w.max, 1e-3)), ImVec2(width, 40.0f));
    }
    int remove = -1;
    for (size_t s = 0; s < value.size(); ++s) {
        ImGui::PushID(int(s));
        float at = number(value[s]["at"]);
        ImGui::SetNextItemWidth(90.0f);
        if (ImGui::SliderFloat("##at", &at, 0.0f, 1.0f, "at %.2f")) {
            value[s]["at"] = at;
            changed = true;
        }
        ImGui::SameLine();
        if (gradient) {
            float c[4] = {1, 1, 1, 1};
            for (size_t k = 0; k < 4 && k < value[s][key].size(); ++k)
                c[k] = number(value[s][key][k]);
            if (ImGui::ColorEdit4("##c", c, ImGuiColorEditFlags_AlphaBar)) {
                value[s][key] = json::array({c[0], c[1], c[2], c[3]});
                changed = true;
            }
        } else {
            // A drag over the reader's whole range (a slider to 100 is too coarse near 1).
            float v = number(value[s][key]);
            ImGui::SetNextItemWidth(160.0f);
            if (ImGui::DragFloat("##v", &v, 0.01f, float(widgetLowest(w)), float(w.max),
                                 w.format.c_str(), ImGuiSliderFlags_AlwaysClamp)) {
                value[s][key] = v;
                changed = true;
            }
        }
        if (value.size() > 2) {
            ImGui::SameLine();
            if (ImGui::SmallButton("-")) remove = int(s);
        }
        ImGui::PopID();
    }
    if (remove >= 0) {
        value.erase(size_t(remove));
        changed = true;
    }
    if (value.size() < size_t(kMaxStops) && ImGui::SmallButton("+ stop")) {
        json last = value.back();
        value.back()["at"] = 0.5f * (number(value[value.size() - 2]["at"]) + 1.0f);
        last["at"] = 1.0;
        value.push_back(last);
        changed = true;
    }
    // Stops go from head to tail: keep them in order of "at".
    if (changed) {
        std::vector<json> sorted(value.begin(), value.end());
        std::stable_sort(sorted.begin(), sorted.end(), [](const json& a, const json& b) {
            return number(a["at"]) < number(b["at"]);
        });
        value = json(sorted);
    }
    return changed;
}

// One key's widget; true when the user changed `value` (the new value in it).
bool editParam(const ParamInfo& p, const PanelWidget& w, const std::vector<ParamInfo>& table,
               json& value) {
    using K = PanelWidget::Kind;
    const char* label = p.key.c_str();
    switch (w.kind) {
    case K::None:
        return false;
    case K::Slider:
    case K::Drag: {
        if (!value.is_number()) { // no default: absent until set
            ImGui::TextDisabled("%s: not set", label);
            ImGui::SameLine();
            if (!ImGui::SmallButton("set")) return false;
            value = std::max(widgetLowest(w), std::min(w.max, 1.0));
            return true;
        }
        float v = value.get<float>();
        const float low = float(widgetLowest(w)), high = float(w.max);
        bool changed = false;
        if (w.kind == K::Slider)
            changed = ImGui::SliderFloat(label, &v, low, high, w.format.c_str(),
                                         w.logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
        else
            changed = ImGui::DragFloat(label, &v, std::max(1e-3f, std::abs(v) * 0.01f), low, high,
                                       w.format.c_str(), ImGuiSliderFlags_AlwaysClamp);
        if (changed) value = double(std::clamp(v, low, high));
        return changed;
    }
    case K::IntSlider:
    case K::IntDrag: {
        int v = value.is_number() ? value.get<int>() : int(w.min);
        const int low = int(w.min), high = int(std::min(w.max, 2e9));
        const bool changed =
            w.kind == K::IntSlider
                ? ImGui::SliderInt(label, &v, low, high)
                : ImGui::DragInt(label, &v, 1.0f, low, high, "%d", ImGuiSliderFlags_AlwaysClamp);
        if (changed) value = std::clamp(v, low, high);
        return changed;
    }
    case K::Checkbox: {
        bool v = value.is_boolean() && value.get<bool>();
        if (!ImGui::Checkbox(label, &v)) return false;
        value = v;
        return true;
    }
    case K::Combo: {
        const std::string current = value.is_string() ? value.get<std::string>() : "";
        bool changed = false;
        if (ImGui::BeginCombo(label, current.c_str())) {
            for (const std::string& c : p.choices)
                if (ImGui::Selectable(c.c_str(), c == current) && c != current) {
                    value = c;
                    changed = true;
                }
            ImGui::EndCombo();
        }
        return changed;
    }
    case K::Colour: {
        float c[4] = {1, 1, 1, 1};
        if (value.is_array())
            for (size_t k = 0; k < 4 && k < value.size(); ++k)
                c[k] = number(value[k]);
        if (!ImGui::ColorEdit4(label, c, ImGuiColorEditFlags_AlphaBar)) return false;
        value = json::array({c[0], c[1], c[2], c[3]});
        return true;
    }
    case K::Vec3: {
        float v[3] = {0, 0, 0};
        if (value.is_array())
            for (size_t k = 0; k < 3 && k < value.size(); ++k)
                v[k] = number(value[k]);
        if (!ImGui::DragFloat3(label, v, 0.01f, float(w.min), float(w.max), w.format.c_str(),
                               ImGuiSliderFlags_AlwaysClamp))
            return false;
        value = json::array({v[0], v[1], v[2]});
        return true;
    }
    case K::IntVec3: {
        int v[3] = {int(w.min), int(w.min), int(w.min)};
        if (value.is_array())
            for (size_t k = 0; k < 3 && k < value.size(); ++k)
                v[k] = value[k].is_number() ? value[k].get<int>() : int(w.min);
        if (!ImGui::DragInt3(label, v, 0.2f, int(w.min), int(w.max), "%d",
                             ImGuiSliderFlags_AlwaysClamp))
            return false;
        value = json::array({v[0], v[1], v[2]});
        return true;
    }
    case K::NameList:
    case K::Text: {
        std::string text;
        if (value.is_string()) text = value.get<std::string>();
        if (value.is_array())
            for (const json& n : value)
                text += (text.empty() ? "" : ", ") + (n.is_string() ? n.get<std::string>() : "");
        char buffer[512];
        std::snprintf(buffer, sizeof buffer, "%s", text.c_str());
        if (!ImGui::InputText(label, buffer, sizeof buffer, ImGuiInputTextFlags_EnterReturnsTrue))
            return false;
        if (w.kind == K::Text) {
            value = std::string(buffer);
        } else {
            value = json::array();
            std::string name;
            for (const char* c = buffer;; ++c) {
                if (*c == ',' || *c == 0) {
                    const size_t a = name.find_first_not_of(' '), b = name.find_last_not_of(' ');
                    if (a != std::string::npos) value.push_back(name.substr(a, b - a + 1));
                    name.clear();
                    if (*c == 0) break;
                } else {
                    name += *c;
                }
            }
        }
        return true;
    }
    case K::Gradient:
    case K::Curve:
        return editStops(p, w, table, value);
    }
    return false;
}

} // namespace

void editSection(scene::SceneDocument& doc, const std::string& section, PanelRequests& out) {
    const std::vector<ParamInfo> table = doc.params(section);
    ImGui::PushID(section.c_str());
    for (const ParamInfo& p : table) {
        if (p.key.find("[].") != std::string::npos) continue;
        const PanelWidget w = widgetFor(p, table);
        if (w.kind == PanelWidget::Kind::None) continue;
        ImGui::PushID(p.key.c_str());
        const bool given = doc.given(section, p.key);
        if (!given) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.6f, 0.6f, 0.6f, 1.0f));
        json value = p.fallback;
        const bool changed = editParam(p, w, table, value);
        if (!given) ImGui::PopStyleColor();
        if (given && p.key != "name") {
            ImGui::SameLine();
            if (ImGui::SmallButton("x")) { // back to the default
                if (Status s = doc.reset(section, p.key); s)
                    out.edited = true;
                else
                    out.refused = s.error().message;
            }
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("back to the default");
        } else if (!given && p.absentDiffers && ImGui::IsItemHovered()) {
            ImGui::SetTooltip("not set: chosen for you");
        }
        if (changed) {
            if (Status s = doc.set(section, p.key, value); s)
                out.edited = true;
            else
                out.refused = s.error().message;
        }
        ImGui::PopID();
    }
    ImGui::PopID();
}

} // namespace mfx::app

#endif
