// Reading a scene file's JSON (internal to core/scene): one object at a time with its key path,
// so that every refusal names where it is (`effects[2].bones[0]: ...`). The readers throw
// SceneError, which parseScene turns into one Error.
//
// The same readers describe what they read: an Object made with a Description reads nothing
// (every key "is there" and reads as its default) and records each key it is asked for with its
// type, range, choices and default. That record is the parameter table (core/scene/scene_params.h)
// the viewer's panel and the scene writer use, so the table and the validation are one code.
#pragma once

#include "core/scene/scene_params.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace mfx::scene::detail {

using json = nlohmann::json;

// Thrown inside the parser only, caught at its top and turned into an Error.
struct SceneError {
    std::string message;
};

[[noreturn]] inline void fail(const std::string& path, const std::string& what) {
    throw SceneError{path + ": " + what};
}

inline std::string typeOf(const json& j) {
    if (j.is_null()) return "null";
    if (j.is_boolean()) return "a boolean";
    if (j.is_number()) return "a number";
    if (j.is_string()) return "a string";
    if (j.is_array()) return "an array";
    return "an object";
}

inline std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names)
        out += (out.empty() ? "" : ", ") + n;
    return out;
}

inline std::string formatNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

using ParamInfo = scene::ParamInfo;

// What describe mode records: every key read, in order, and the keys whose presence was checked
// (has()), whose absence means something of its own.
struct Description {
    std::vector<ParamInfo> params;
    std::vector<std::string> presenceChecked;
};

// The description's keys, each once (where a reader asks for a key twice, its first reading),
// marked absentDiffers where the reader checked whether the key is there.
inline std::vector<ParamInfo> uniqueParams(const Description& described) {
    std::vector<ParamInfo> out;
    for (const ParamInfo& p : described.params)
        if (std::none_of(out.begin(), out.end(),
                         [&](const ParamInfo& q) { return q.key == p.key; }))
            out.push_back(p);
    for (ParamInfo& p : out)
        p.absentDiffers = std::count(described.presenceChecked.begin(),
                                     described.presenceChecked.end(), p.key) > 0;
    return out;
}

// One JSON object being read, with its key path for errors.
class Object {
public:
    Object(const json& j, std::string path) : j_(j), path_(std::move(path)) {
        if (!j_.is_object())
            fail(path_.empty() ? "scene" : path_, "expected an object, got " + typeOf(j_));
    }
    // Describe mode: records into `described` every key read (keys prefixed by `prefix`). Every
    // key is there (has() is true), and reads as `context` has it (checked as usual), else as its
    // default: a context of {"variant": "multi"} describes what that variant reads.
    explicit Object(Description& described, const json& context = emptyObject(),
                    std::string prefix = {})
        : j_(context.is_object() ? context : emptyObject()), described_(&described),
          prefix_(std::move(prefix)) {}
    bool describing() const { return described_ != nullptr; }

    // Refuses keys outside `allowed`; `elsewhere` are keys that exist for other effect types.
    void onlyKeys(const std::vector<std::string>& allowed,
                  const std::vector<std::string>& elsewhere = {},
                  const std::string& elsewhereWhy = {}) const {
        for (auto it = j_.begin(); it != j_.end(); ++it) {
            if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
            if (std::find(elsewhere.begin(), elsewhere.end(), it.key()) != elsewhere.end())
                fail(at(it.key()), elsewhereWhy);
            fail(at(it.key()), "unknown key; keys here are: " + join(allowed));
        }
    }

    bool has(const std::string& key) const {
        // A presence check: the key's absence means something of its own.
        if (described_) described_->presenceChecked.push_back(prefix_ + key);
        return described_ || j_.contains(key);
    }
    // Whether the file (in describe mode: the context) gives `key`: for checks between keys.
    bool given(const std::string& key) const { return j_.contains(key); }
    // Whether the file gives `key` as null.
    bool null(const std::string& key) const { return given(key) && j_.at(key).is_null(); }
    std::vector<std::string> keys() const {
        std::vector<std::string> out;
        for (auto it = j_.begin(); it != j_.end(); ++it)
            out.push_back(it.key());
        return out;
    }
    std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
    const json& raw(const std::string& key) const { return j_.at(key); }

    double number(const std::string& key, double fallback, double low, double high,
                  bool lowOpen = false) const {
        if (described_) {
            record(key, ParamInfo::Type::Number, fallback, low, high).lowOpen = lowOpen;
            if (!given(key)) return fallback;
        }
        if (!has(key)) return fallback;
        return checkNumber(j_.at(key), at(key), low, high, lowOpen);
    }
    std::optional<double> optionalNumber(const std::string& key, double low, double high,
                                         bool lowOpen = false) const {
        if (described_) {
            record(key, ParamInfo::Type::Number, nullptr, low, high).lowOpen = lowOpen;
            if (!given(key)) return std::nullopt;
        }
        if (!has(key) || j_.at(key).is_null()) return std::nullopt;
        return checkNumber(j_.at(key), at(key), low, high, lowOpen);
    }
    uint32_t integer(const std::string& key, uint32_t fallback, uint32_t low, uint32_t high) const {
        if (described_) {
            record(key, ParamInfo::Type::Integer, fallback, low, high);
            if (!given(key)) return fallback;
        }
        if (!has(key)) return fallback;
        return checkInteger(j_.at(key), at(key), low, high);
    }
    bool boolean(const std::string& key, bool fallback) const {
        if (described_) {
            record(key, ParamInfo::Type::Boolean, fallback);
            if (!given(key)) return fallback;
        }
        if (!has(key)) return fallback;
        const json& v = j_.at(key);
        if (!v.is_boolean()) fail(at(key), "expected true or false, got " + typeOf(v));
        return v.get<bool>();
    }
    std::string string(const std::string& key, const std::string& fallback) const {
        if (described_) {
            record(key, ParamInfo::Type::String, fallback);
            if (!given(key)) return fallback;
        }
        if (!has(key)) return fallback;
        const json& v = j_.at(key);
        if (!v.is_string()) fail(at(key), "expected a string, got " + typeOf(v));
        return v.get<std::string>();
    }
    // The name of one of the scene's characters, checked against them once the scene is read;
    // absent: "" (the first).
    std::string characterName(const std::string& key) const {
        if (described_) {
            record(key, ParamInfo::Type::CharacterName, json()).absentDiffers = true;
            if (!given(key)) return {};
        }
        if (!has(key)) return {};
        const json& v = j_.at(key);
        if (!v.is_string()) fail(at(key), "expected a character's name, got " + typeOf(v));
        return v.get<std::string>();
    }
    std::string choice(const std::string& key, const std::string& fallback,
                       const std::vector<std::string>& choices) const {
        if (described_) {
            record(key, ParamInfo::Type::Choice, fallback).choices = choices;
            if (!given(key))
                return fallback.empty() && !choices.empty() ? choices.front() : fallback;
        }
        // The file's value is looked at in place: it is only copied once it is known to be a
        // string (a deep array in its place would make a deep copy).
        const json* given = j_.contains(key) ? &j_.at(key) : nullptr;
        if (given && !given->is_string()) fail(at(key), "expected a string, got " + typeOf(*given));
        const std::string v = given ? given->get<std::string>() : fallback;
        if (std::find(choices.begin(), choices.end(), v) == choices.end())
            fail(at(key), "\"" + v + "\" is not one of: " + join(choices));
        return v;
    }
    glm::vec3 vec3(const std::string& key, glm::vec3 fallback, double low = -1e6,
                   double high = 1e6) const {
        if (described_) {
            record(key, ParamInfo::Type::Vec3, json::array({fallback.x, fallback.y, fallback.z}),
                   low, high);
            if (!given(key)) return fallback;
        }
        if (!has(key)) return fallback;
        const std::vector<double> v = numbers(key, 3, 3, low, high);
        return {float(v[0]), float(v[1]), float(v[2])};
    }
    // An RGB or RGBA colour in [0, 1].
    glm::vec4 colour(const std::string& key, glm::vec4 fallback) const {
        if (described_) {
            ParamInfo& p =
                record(key, ParamInfo::Type::Colour,
                       json::array({fallback.r, fallback.g, fallback.b, fallback.a}), 0.0, 1.0);
            p.minCount = 3;
            p.maxCount = 4;
            if (!given(key)) return fallback;
        }
        if (!has(key)) return fallback;
        const std::vector<double> v = numbers(key, 3, 4, 0.0, 1.0);
        return {float(v[0]), float(v[1]), float(v[2]), v.size() == 4 ? float(v[3]) : 1.0f};
    }
    std::vector<std::string> strings(const std::string& key) const {
        std::vector<std::string> out;
        if (described_) {
            record(key, ParamInfo::Type::Strings, json::array());
            if (!given(key)) return out;
        }
        if (!has(key)) return out;
        const json& v = j_.at(key);
        if (!v.is_array()) fail(at(key), "expected an array of names, got " + typeOf(v));
        for (size_t i = 0; i < v.size(); ++i) {
            if (!v[i].is_string())
                fail(at(key) + "[" + std::to_string(i) + "]",
                     "expected a name, got " + typeOf(v[i]));
            out.push_back(v[i].get<std::string>());
        }
        return out;
    }
    // The objects of an array of `minCount` to `maxCount` objects, each named by its index.
    // Described: one object, whose keys are recorded as "key[].<its key>".
    std::vector<Object> objects(const std::string& key, size_t minCount, size_t maxCount) const {
        if (described_) {
            ParamInfo& p = record(key, ParamInfo::Type::Objects, nullptr);
            p.minCount = minCount;
            p.maxCount = maxCount;
            const json* first = given(key) && j_.at(key).is_array() && !j_.at(key).empty()
                                    ? &j_.at(key)[0]
                                    : &emptyObject();
            std::vector<Object> one;
            one.push_back(Object(*described_, *first, prefix_ + key + "[]."));
            return one;
        }
        const json& v = j_.at(key);
        if (!v.is_array() || v.size() < minCount || v.size() > maxCount)
            fail(at(key),
                 "expected an array of " + std::to_string(minCount) + " to " +
                     std::to_string(maxCount) + " objects, got " +
                     (v.is_array() ? "an array of " + std::to_string(v.size()) : typeOf(v)));
        std::vector<Object> out;
        for (size_t i = 0; i < v.size(); ++i)
            out.emplace_back(v[i], at(key) + "[" + std::to_string(i) + "]");
        return out;
    }
    std::vector<double> numbers(const std::string& key, size_t minCount, size_t maxCount,
                                double low, double high) const {
        if (described_) {
            ParamInfo& p = record(key, ParamInfo::Type::Numbers, nullptr, low, high);
            p.minCount = minCount;
            p.maxCount = maxCount;
            if (!given(key))
                return std::vector<double>(minCount, std::max(low, std::min(high, 1.0)));
        }
        const json& v = j_.at(key);
        const std::string count =
            minCount == maxCount ? std::to_string(minCount)
                                 : std::to_string(minCount) + " or " + std::to_string(maxCount);
        if (!v.is_array() || v.size() < minCount || v.size() > maxCount)
            fail(at(key),
                 "expected an array of " + count + " numbers, got " +
                     (v.is_array() ? "an array of " + std::to_string(v.size()) : typeOf(v)));
        std::vector<double> out;
        for (size_t i = 0; i < v.size(); ++i)
            out.push_back(checkNumber(v[i], at(key) + "[" + std::to_string(i) + "]", low, high));
        return out;
    }

private:
    static const json& emptyObject() {
        static const json empty = json::object();
        return empty;
    }
    ParamInfo& record(const std::string& key, ParamInfo::Type type, json fallback, double low = 0.0,
                      double high = 0.0) const {
        described_->params.push_back(
            ParamInfo{prefix_ + key, type, low, high, false, 0, 0, {}, std::move(fallback)});
        return described_->params.back();
    }

    static double checkNumber(const json& v, const std::string& path, double low, double high,
                              bool lowOpen = false) {
        if (!v.is_number()) fail(path, "expected a number, got " + typeOf(v));
        const double d = v.get<double>();
        if (!std::isfinite(d)) fail(path, "must be a finite number");
        const std::string range =
            std::string(lowOpen ? "(" : "[") + formatNumber(low) + ", " + formatNumber(high) + "]";
        if (d < low || d > high || (lowOpen && d == low))
            fail(path, formatNumber(d) + " is outside " + range);
        // Every number of a scene is stored as a 32-bit float: the range holds for what is
        // stored, not only for the double the file spells (1e-300 is in (0, 100] but becomes 0).
        const float stored = float(d);
        if (stored < float(low) || stored > float(high) || (lowOpen && stored <= float(low)))
            fail(path, formatNumber(d) + " is outside " + range +
                           " as a 32-bit float (it becomes " + formatNumber(double(stored)) + ")");
        return double(stored);
    }
    static uint32_t checkInteger(const json& v, const std::string& path, uint32_t low,
                                 uint32_t high) {
        if (!v.is_number()) fail(path, "expected a whole number, got " + typeOf(v));
        const double d = v.get<double>();
        if (!std::isfinite(d) || d != std::floor(d)) fail(path, "expected a whole number");
        if (d < low || d > high)
            fail(path, formatNumber(d) + " is outside " + std::to_string(low) + ".." +
                           std::to_string(high));
        return uint32_t(d);
    }

    const json& j_;
    std::string path_;
    Description* described_ = nullptr;
    std::string prefix_;
};

} // namespace mfx::scene::detail
