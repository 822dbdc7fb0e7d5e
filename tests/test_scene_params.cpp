// The scene file's parameter table (core/scene/scene_params.h), which the viewer's panel builds
// its widgets from, is the scene reader's own validation: every key of every section and effect
// kind is in it, and every range, choice and type in it is exactly what a scene file is held to
// (values at its bounds are read, values past them are refused naming the key).
#include "core/scene/effect_kinds.h"
#include "core/scene/scene.h"
#include "core/scene/scene_params.h"
#include "tests/scene_params_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace mfx::test {
namespace {

using nlohmann::json;
using scene::ParamInfo;

// An effect kind's keys over every value of each of its choices (an afterimage's variant decides
// which look keys it reads), each with the context it was described in.
std::vector<std::pair<json, ParamInfo>> everyEffectParam(const std::string& type) {
    std::vector<std::pair<json, ParamInfo>> out;
    std::set<std::string> seen;
    for (const json& context : choiceContexts(type))
        for (const ParamInfo& p : scene::effectParams(type, context))
            if (seen.insert(p.key).second) out.emplace_back(context, p);
    return out;
}

// A scene whose `section` (or, with an effect type, its one effect, over `context`) gives `key`
// as `value`. A key of the objects of an array (stops) is given in two objects, their other keys
// (`siblings`) at their defaults.
std::string sceneWith(const std::string& section, const json& context, const std::string& key,
                      const json& value, const std::vector<ParamInfo>& siblings) {
    json doc = {{"effects", json::array()}};
    json object = context;
    const size_t stops = key.find("[].");
    if (stops == std::string::npos) {
        object[key] = value;
    } else { // a key of the objects of an array: two of them, the key at both
        const std::string array = key.substr(0, stops), inner = key.substr(stops + 3);
        json first = {{"at", 0.0}}, second = {{"at", 1.0}};
        for (const ParamInfo& s : siblings)
            if (s.key.rfind(array + "[].", 0) == 0 && !s.fallback.is_null()) {
                first[s.key.substr(stops + 3)] = s.fallback;
                second[s.key.substr(stops + 3)] = s.fallback;
            }
        first[inner] = value;
        second[inner] = value;
        object[array] = json::array({first, second});
    }
    if (section == "lights")
        doc["lights"] = json::array({object});
    else if (std::find(scene::sceneSections().begin(), scene::sceneSections().end(), section) !=
             scene::sceneSections().end())
        doc[section] = object;
    else
        doc["effects"] = json::array({object});
    return doc.dump();
}

// Checks that `value` is read (`accepted`) or refused with an error naming `key`.
void expectRead(const std::string& section, const json& context, const ParamInfo& p,
                const json& value, bool accepted) {
    const std::vector<ParamInfo> siblings =
        std::find(scene::sceneSections().begin(), scene::sceneSections().end(), section) !=
                scene::sceneSections().end()
            ? scene::sectionParams(section)
            : scene::effectParams(section, context);
    const std::string text = sceneWith(section, context, p.key, value, siblings);
    const Result<scene::Scene> read = scene::parseScene(text, "params.json");
    if (accepted) {
        EXPECT_TRUE(read.ok()) << section << "." << p.key << " = " << value.dump()
                               << " is in the table's range but refused: "
                               << (read.ok() ? "" : read.error().message);
    } else {
        ASSERT_FALSE(read.ok()) << section << "." << p.key << " = " << value.dump()
                                << " is outside the table's range but read";
        const std::string leaf =
            p.key.substr(p.key.rfind('.') == std::string::npos ? 0 : p.key.rfind('.') + 1);
        EXPECT_NE(read.error().message.find(leaf), std::string::npos) << read.error().message;
    }
}

// Values at the bounds of `p` are read; values past them are refused.
void checkRange(const std::string& section, const json& givenContext, const ParamInfo& p) {
    using T = ParamInfo::Type;
    const double span = std::max(1.0, std::abs(p.high - p.low));
    // The ranges between keys rather than of one key. "end" must be after "start" (0 by
    // default), so its lowest value read is just above its bound. The camera's "near" must be
    // before "far": each is checked with the other out of its way.
    const bool afterStart = p.key == "end";
    json context = givenContext;
    if (section == "camera" && p.key == "near") context["far"] = 1e6;
    if (section == "camera" && p.key == "far") context["near"] = 1e-9;
    switch (p.type) {
    case T::Number:
        expectRead(section, context, p, p.lowOpen || afterStart ? p.low + 1e-6 * span : p.low,
                   true);
        expectRead(section, context, p, p.high, true);
        expectRead(section, context, p, p.lowOpen ? p.low : p.low - 1e-3 * span, false);
        expectRead(section, context, p, p.high + 1e-3 * span, false);
        expectRead(section, context, p, "1", false);
        break;
    case T::Integer:
        expectRead(section, context, p, uint32_t(p.low), true);
        expectRead(section, context, p, uint32_t(p.high), true);
        if (p.low > 0) expectRead(section, context, p, uint32_t(p.low) - 1, false);
        expectRead(section, context, p, uint64_t(p.high) + 1, false);
        expectRead(section, context, p, p.low + 0.5, false);
        break;
    case T::Boolean:
        expectRead(section, context, p, true, true);
        expectRead(section, context, p, false, true);
        expectRead(section, context, p, 1, false);
        break;
    case T::Choice:
        for (const std::string& c : p.choices)
            expectRead(section, context, p, c, true);
        expectRead(section, context, p, "no such choice", false);
        break;
    case T::Colour:
        expectRead(section, context, p, json::array({0, 0, 0}), true);
        expectRead(section, context, p, json::array({1, 1, 1, 1}), true);
        expectRead(section, context, p, json::array({1.01, 0, 0}), false);
        expectRead(section, context, p, json::array({0, 0}), false);
        break;
    case T::Vec3:
        expectRead(section, context, p, p.fallback, true);
        expectRead(section, context, p, json::array({p.high * 2.0, 0, 0}), false);
        break;
    case T::Numbers:
        expectRead(section, context, p, std::vector<double>(p.minCount, p.low), true);
        expectRead(section, context, p, std::vector<double>(p.maxCount, p.high), true);
        expectRead(section, context, p, std::vector<double>(p.maxCount + 1, p.low), false);
        expectRead(section, context, p, std::vector<double>(p.minCount, p.high + 1.0), false);
        break;
    case T::Strings:
        expectRead(section, context, p, json::array({"a", "b"}), true);
        expectRead(section, context, p, json::array({1}), false);
        break;
    case T::String:
        expectRead(section, context, p, "something", true);
        expectRead(section, context, p, 2, false);
        break;
    case T::CharacterName: // the scenes written here have one character, named "p1"
        // An impact's target is another character than the one it follows (p1 too).
        expectRead(section, context, p, "p1", p.key != "target");
        expectRead(section, context, p, "p2", false);
        expectRead(section, context, p, 2, false);
        break;
    case T::Objects: // their keys are checked one by one
        expectRead(section, context, p, json::array(), p.minCount == 0);
        break;
    }
}

TEST(SceneParams, EveryKeyOfEveryEffectKindIsInTheTable) {
    for (const scene::EffectKindEntry& kind : scene::effectKinds()) {
        std::set<std::string> described;
        for (const auto& [context, p] : everyEffectParam(kind.type))
            described.insert(p.key.substr(0, p.key.find("[]")));
        std::vector<std::string> keys = scene::commonEffectKeys();
        keys.insert(keys.end(), kind.keys.begin(), kind.keys.end());
        for (const std::string& key : keys)
            EXPECT_TRUE(described.count(key)) << kind.type << "." << key << " has no entry";
        for (const std::string& key : described)
            EXPECT_NE(std::find(keys.begin(), keys.end(), key), keys.end())
                << kind.type << "." << key << " is described but is not a key of the kind";
    }
}

TEST(SceneParams, EveryEffectKeysRangeIsTheOneTheSceneReaderChecks) {
    for (const scene::EffectKindEntry& kind : scene::effectKinds())
        for (const auto& [context, p] : everyEffectParam(kind.type)) {
            if (p.key == "type") continue;
            json c = context;
            c["type"] = kind.type;
            SCOPED_TRACE(std::string(kind.type) + " " + context.dump() + " " + p.key);
            checkRange(kind.type, c, p);
        }
}

TEST(SceneParams, EverySectionKeysRangeIsTheOneTheSceneReaderChecks) {
    for (const std::string& section : scene::sceneSections()) {
        const std::vector<ParamInfo> params = scene::sectionParams(section);
        EXPECT_FALSE(params.empty()) << section;
        for (const ParamInfo& p : params) {
            SCOPED_TRACE(section + "." + p.key);
            checkRange(section, json::object(), p);
        }
    }
}

TEST(SceneParams, DefaultsAreTheReadersDefaults) {
    // A few spot checks against the structs' own defaults.
    const auto speed = scene::effectParams("speed_lines");
    ASSERT_TRUE(scene::findParam(speed, "lifetime"));
    EXPECT_EQ(scene::findParam(speed, "lifetime")->fallback, 12);
    EXPECT_EQ(scene::findParam(speed, "blend")->fallback, "alpha");
    const auto post = scene::sectionParams("post");
    EXPECT_NEAR(scene::findParam(post, "bloom")->fallback.get<double>(), 0.1, 1e-6);
    EXPECT_EQ(scene::findParam(post, "tone_map")->fallback, "aces");
    // What depends on a choice: the afterimage's speed_lines variant reads the ribbon's keys.
    EXPECT_FALSE(scene::findParam(scene::effectParams("afterimage_smear"), "facing"));
    EXPECT_TRUE(scene::findParam(
        scene::effectParams("afterimage_smear", {{"variant", "speed_lines"}}), "facing"));
    EXPECT_THROW(scene::effectParams("no_such_type"), std::invalid_argument);
}

} // namespace
} // namespace mfx::test
