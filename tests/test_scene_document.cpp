// The scene document the viewer's panel edits (core/scene/scene_document.h): every key of every
// section and effect kind set through it, saved and loaded again, gives the same scene; what is
// saved holds only the keys that were set, in the reader's order; a value the reader refuses
// leaves the document as it was.
#include "core/scene/effect_kinds.h"
#include "core/scene/scene_document.h"
#include "tests/scene_params_util.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace mfx::test {
namespace {

using nlohmann::json;
using scene::ParamInfo;
using scene::SceneDocument;

std::filesystem::path documentDir() {
    const std::filesystem::path dir = std::filesystem::path(MFX_TEST_OUTPUT_DIR) / "document";
    std::filesystem::create_directories(dir);
    return dir;
}

std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// A valid value of `p` other than its default, the `attempt`-th of a few (a value read alone may
// be refused beside another key's default: a camera's near plane beyond its far one).
json otherValue(const ParamInfo& p, int attempt) {
    using T = ParamInfo::Type;
    const double fractions[] = {0.37, 0.81, 0.13};
    const double f = fractions[attempt % 3];
    switch (p.type) {
    case T::Number: {
        if (attempt == 3 && p.fallback.is_number()) // between the bound and the default
            return p.low + 0.5 * (p.fallback.get<double>() - p.low);
        const double high = std::min(p.high, p.low + 1000.0);
        double v = p.low + f * (high - p.low);
        if (p.fallback.is_number() && v == p.fallback.get<double>())
            v = p.low + 0.5 * f * (high - p.low);
        return v;
    }
    case T::Integer: {
        uint32_t v = uint32_t(p.low + f * (std::min(p.high, p.low + 100.0) - p.low));
        if (p.fallback.is_number() && v == p.fallback.get<uint32_t>())
            v = v < p.high ? v + 1 : v - 1;
        return v;
    }
    case T::Boolean:
        return !(p.fallback.is_boolean() && p.fallback.get<bool>());
    case T::Choice:
        for (const std::string& c : p.choices)
            if (json(c) != p.fallback) return c;
        return p.choices.front();
    case T::Colour:
        return json::array({0.25, 0.5, f, 1.0});
    case T::Vec3:
        return json::array({0.5, 1.25, f});
    case T::Numbers:
        return std::vector<double>(p.minCount, std::min(p.high, p.low + 4.0));
    case T::Strings:
        return json::array({"foot_r", "toe_r"});
    case T::String:
        return "edited " + std::to_string(attempt);
    case T::CharacterName: // the second of the two characters of the effects' documents
        return "p2";
    case T::Objects:
        return json();
    }
    return json();
}

// Two stops for the array `p` (its objects' keys `params` at their defaults, "at" 0 and 1, the
// value of the second one changed).
json stopsFor(const ParamInfo& p, const std::vector<ParamInfo>& params) {
    json first = json::object(), second = json::object();
    for (const ParamInfo& q : params)
        if (q.key.rfind(p.key + "[].", 0) == 0) {
            const std::string inner = q.key.substr(p.key.size() + 3);
            first[inner] = inner == "at" ? json(0.0) : q.fallback;
            second[inner] = inner == "at" ? json(1.0) : otherValue(q, 1);
        }
    return json::array({first, second});
}

// Sets `p` of `section` in `doc` to a value other than its default; false when none is read.
bool setOther(SceneDocument& doc, const std::string& section, const ParamInfo& p,
              const std::vector<ParamInfo>& params, std::string& error) {
    if (p.type == ParamInfo::Type::Objects) {
        const Status s = doc.set(section, p.key, stopsFor(p, params));
        if (!s) error = s.error().message;
        return s.ok();
    }
    for (int attempt = 0; attempt < 4; ++attempt) {
        const Status s = doc.set(section, p.key, otherValue(p, attempt));
        if (s) return true;
        error = s.error().message;
    }
    return false;
}

// For each key of `section` of the document `start`: set, saved, loaded, the same.
void roundTripEveryKey(const std::string& start, const std::string& section,
                       const std::string& label) {
    Result<SceneDocument> base = SceneDocument::fromText(start, "start.json");
    ASSERT_TRUE(base.ok()) << base.error().message;
    const std::vector<ParamInfo> params = base.value().params(section);
    ASSERT_FALSE(params.empty()) << label;
    const std::filesystem::path file = documentDir() / (label + ".json");
    for (const ParamInfo& p : params) {
        if (p.key == "type" || p.key.find("[].") != std::string::npos) continue;
        SCOPED_TRACE(label + " " + section + "." + p.key);
        SceneDocument doc = base.value();
        std::string error;
        ASSERT_TRUE(setOther(doc, section, p, params, error)) << error;
        ASSERT_TRUE(doc.given(section, p.key));
        ASSERT_TRUE(doc.save(file).ok());
        Result<SceneDocument> loaded = SceneDocument::load(file);
        ASSERT_TRUE(loaded.ok()) << loaded.error().message << "\n" << readText(file);
        EXPECT_EQ(loaded.value().document(), doc.document()) << readText(file);
        EXPECT_EQ(loaded.value().text(), readText(file)) << "the saved text is the document's";
        // The same scene: each key reads the same, and the effects are the same kinds and names
        // with the same keys given.
        const std::vector<ParamInfo> again = loaded.value().params(section);
        ASSERT_EQ(again.size(), doc.params(section).size());
        for (size_t i = 0; i < again.size(); ++i)
            EXPECT_EQ(again[i].fallback, doc.params(section)[i].fallback) << again[i].key;
        const scene::Scene& a = loaded.value().scene();
        const scene::Scene& b = doc.scene();
        ASSERT_EQ(a.effects.size(), b.effects.size());
        for (size_t e = 0; e < a.effects.size(); ++e) {
            EXPECT_EQ(std::string(a.effects[e].type()), b.effects[e].type());
            EXPECT_EQ(a.effects[e].name, b.effects[e].name);
            EXPECT_EQ(a.effects[e].givenKeys, b.effects[e].givenKeys);
        }
    }
}

TEST(SceneDocument, EveryKeyOfEveryEffectKindRoundTripsThroughSaveAndLoad) {
    for (const scene::EffectKindEntry& kind : scene::effectKinds()) {
        int n = 0;
        for (json effect : choiceContexts(kind.type)) {
            effect["type"] = kind.type;
            // Two characters: an effect may follow the second, and an impact land on it.
            const json doc = {{"characters", json::array({json::object(), json::object()})},
                              {"effects", json::array({effect})}};
            roundTripEveryKey(doc.dump(), "effects[0]",
                              std::string(kind.type) + "_" + std::to_string(n++));
        }
    }
}

TEST(SceneDocument, EveryKeyOfEverySectionRoundTrips) {
    const std::string start = R"({"lights": [{}], "effects": []})";
    for (const std::string& section : scene::sceneSections())
        roundTripEveryKey(start, section == "lights" ? "lights[0]" : section, section);
}

// A character of a "characters" list: each of its keys set, saved and read back, as the
// single "character"'s are.
TEST(SceneDocument, EveryKeyOfACharacterInAListRoundTrips) {
    const std::string start = R"({"characters": [{"name": "hero"}, {}], "effects": []})";
    roundTripEveryKey(start, "characters[1]", "characters");
}

TEST(SceneDocument, SavesOnlyTheKeysSetInTheReadersOrder) {
    Result<SceneDocument> read = SceneDocument::fromText(
        R"({"effects": [{"width": 0.03, "name": "lines", "type": "speed_lines"}],
            "camera": {"fov_degrees": 35, "position": [1, 2, 3]}})",
        "order.json");
    ASSERT_TRUE(read.ok()) << read.error().message;
    SceneDocument doc = std::move(read).value();
    ASSERT_TRUE(doc.set("effects[0]", "colour", json::array({1, 0, 0, 1})).ok());
    ASSERT_TRUE(doc.set("post", "bloom", 0.25).ok());
    EXPECT_EQ(doc.text(), R"({
  "camera": {
    "position": [1, 2, 3],
    "fov_degrees": 35
  },
  "post": {
    "bloom": 0.25
  },
  "effects": [
    {
      "type": "speed_lines",
      "name": "lines",
      "colour": [1, 0, 0, 1],
      "width": 0.03
    }
  ]
}
)");
    // Back to the default: the key leaves the file.
    ASSERT_TRUE(doc.reset("post", "bloom").ok());
    EXPECT_EQ(doc.text().find("bloom"), std::string::npos);
}

TEST(SceneDocument, ARefusedValueLeavesTheDocumentAsItWas) {
    Result<SceneDocument> read = SceneDocument::fromText(
        R"({"effects": [{"type": "smoke", "radius": 0.1}]})", "refused.json");
    ASSERT_TRUE(read.ok());
    SceneDocument doc = std::move(read).value();
    const std::string before = doc.text();
    const Status s = doc.set("effects[0]", "radius", 11.0);
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("effects[0].radius"), std::string::npos) << s.error().message;
    EXPECT_EQ(doc.text(), before);
    EXPECT_FALSE(doc.set("effects[0]", "no_such_key", 1).ok());
    EXPECT_FALSE(doc.set("effects[3]", "radius", 0.2).ok());
    EXPECT_EQ(doc.text(), before);
}

TEST(SceneDocument, KeysWhoseAbsenceMeansSomethingAreMarked) {
    const auto lines = scene::effectParams("speed_lines");
    EXPECT_TRUE(scene::findParam(lines, "colour")->absentDiffers) << "absent: the mesh's colours";
    EXPECT_TRUE(scene::findParam(lines, "bones")->absentDiffers) << "absent: the fastest limb";
    EXPECT_TRUE(scene::findParam(lines, "stride")->absentDiffers) << "absent: chosen by count";
    EXPECT_FALSE(scene::findParam(lines, "width")->absentDiffers);
    EXPECT_TRUE(scene::findParam(scene::effectParams("smoke"), "cel_bands")->absentDiffers);
}

TEST(SceneDocument, TheBuiltInDefaultSavesToAFileThatReadsAsItself) {
    Result<SceneDocument> read =
        SceneDocument::fromText(scene::defaultSceneJson(), "(built-in default)");
    ASSERT_TRUE(read.ok()) << read.error().message;
    SceneDocument doc = std::move(read).value();
    const std::filesystem::path file = documentDir() / "hero_saved.json";
    ASSERT_TRUE(doc.save(file).ok());
    EXPECT_EQ(doc.where(), file.string());
    Result<SceneDocument> loaded = SceneDocument::load(file);
    ASSERT_TRUE(loaded.ok()) << loaded.error().message;
    EXPECT_EQ(loaded.value().document(), json::parse(scene::defaultSceneJson()));
}

} // namespace
} // namespace mfx::test
