// Reading a scene file's JSON (internal to core/scene): one object at a time with its key path,
// so that every refusal names where it is (`effects[2].bones[0]: ...`). The readers throw
// SceneError, which parseScene turns into one Error.
#pragma once

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

// One JSON object being read, with its key path for errors.
class Object {
public:
    Object(const json& j, std::string path) : j_(j), path_(std::move(path)) {
        if (!j_.is_object())
            fail(path_.empty() ? "scene" : path_, "expected an object, got " + typeOf(j_));
    }

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

    bool has(const std::string& key) const { return j_.contains(key); }
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
        if (!has(key)) return fallback;
        return checkNumber(j_.at(key), at(key), low, high, lowOpen);
    }
    std::optional<double> optionalNumber(const std::string& key, double low, double high,
                                         bool lowOpen = false) const {
        if (!has(key) || j_.at(key).is_null()) return std::nullopt;
        return checkNumber(j_.at(key), at(key), low, high, lowOpen);
    }
    uint32_t integer(const std::string& key, uint32_t fallback, uint32_t low, uint32_t high) const {
        if (!has(key)) return fallback;
        return checkInteger(j_.at(key), at(key), low, high);
    }
    bool boolean(const std::string& key, bool fallback) const {
        if (!has(key)) return fallback;
        const json& v = j_.at(key);
        if (!v.is_boolean()) fail(at(key), "expected true or false, got " + typeOf(v));
        return v.get<bool>();
    }
    std::string string(const std::string& key, const std::string& fallback) const {
        if (!has(key)) return fallback;
        const json& v = j_.at(key);
        if (!v.is_string()) fail(at(key), "expected a string, got " + typeOf(v));
        return v.get<std::string>();
    }
    std::string choice(const std::string& key, const std::string& fallback,
                       const std::vector<std::string>& choices) const {
        const std::string v = string(key, fallback);
        if (std::find(choices.begin(), choices.end(), v) == choices.end())
            fail(at(key), "\"" + v + "\" is not one of: " + join(choices));
        return v;
    }
    glm::vec3 vec3(const std::string& key, glm::vec3 fallback, double low = -1e6,
                   double high = 1e6) const {
        if (!has(key)) return fallback;
        const std::vector<double> v = numbers(key, 3, 3, low, high);
        return {float(v[0]), float(v[1]), float(v[2])};
    }
    // An RGB or RGBA colour in [0, 1].
    glm::vec4 colour(const std::string& key, glm::vec4 fallback) const {
        if (!has(key)) return fallback;
        const std::vector<double> v = numbers(key, 3, 4, 0.0, 1.0);
        return {float(v[0]), float(v[1]), float(v[2]), v.size() == 4 ? float(v[3]) : 1.0f};
    }
    std::vector<std::string> strings(const std::string& key) const {
        std::vector<std::string> out;
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
    std::vector<Object> objects(const std::string& key, size_t minCount, size_t maxCount) const {
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
    static double checkNumber(const json& v, const std::string& path, double low, double high,
                              bool lowOpen = false) {
        if (!v.is_number()) fail(path, "expected a number, got " + typeOf(v));
        const double d = v.get<double>();
        if (!std::isfinite(d)) fail(path, "must be a finite number");
        if (d < low || d > high || (lowOpen && d == low))
            fail(path, formatNumber(d) + " is outside " + (lowOpen ? "(" : "[") +
                           formatNumber(low) + ", " + formatNumber(high) + "]");
        return d;
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
};

} // namespace mfx::scene::detail
