// The scene file's parameter table: every key a section of a scene file may give, with its type,
// range, choices and default, as the scene's reader reads and checks it. It is not written out
// by hand: the readers themselves record what they read when run in describe mode
// (core/scene/json_object.h), so the table and the validation cannot disagree. The viewer's
// panel builds its widgets from it and the scene writer orders and omits keys by it.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace mfx::scene {

// One key. `key` is its path below the section: "width", or "colour_over_life[].at" for a key of
// the objects of an array.
struct ParamInfo {
    enum class Type {
        Number,  // a number in [low, high] ((low, high] when lowOpen)
        Integer, // a whole number in [low, high]
        Boolean,
        String,
        Choice,  // one of `choices`
        Colour,  // 3 or 4 numbers in [0, 1]
        Vec3,    // 3 numbers in [low, high]
        Numbers, // minCount to maxCount numbers in [low, high]
        Strings, // an array of names
        Objects, // an array of minCount to maxCount objects, their keys "key[].<key>"
        // The name of one of the scene's characters (their "name"s): `choices` holds them in a
        // document's table (SceneDocument::params); the reader checks the name against the scene.
        CharacterName,
    };
    std::string key;
    Type type = Type::Number;
    double low = 0.0, high = 0.0;
    bool lowOpen = false;
    size_t minCount = 0, maxCount = 0;
    std::vector<std::string> choices;
    nlohmann::json fallback; // the default; null where the key has none
    // The reader tells an absent key from any value (no "colour": the mesh's colours; no
    // "cel_bands": smooth shading; no "bones" or "meshes": the fastest limb): `fallback` is then
    // only what it reads in the key's place where it needs one.
    bool absentDiffers = false;
};

// The sections of a scene file that are one object: "character", "camera", "lights" (one light),
// "stage", "output", "post".
const std::vector<std::string>& sceneSections();

// The keys of section `section`, in the order the reader reads them (each key once).
std::vector<ParamInfo> sectionParams(const std::string& section);
// The keys of an effect of type `type`: "type", the keys every effect has, then the kind's own.
// `effect` (the effect's object as the file has it) picks what depends on its values (an
// afterimage's variant decides which look keys it has) and is checked as the reader checks it;
// an empty one describes the defaults. Throws std::invalid_argument for an unknown type.
std::vector<ParamInfo> effectParams(const std::string& type,
                                    const nlohmann::json& effect = nlohmann::json::object());

// The entry for `key` in `params`, or null.
const ParamInfo* findParam(const std::vector<ParamInfo>& params, const std::string& key);

} // namespace mfx::scene
