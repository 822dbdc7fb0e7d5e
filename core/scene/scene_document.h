// A scene file as the user edits it (the viewer's panel): its JSON, changed one key at a time,
// each change checked by the scene reader before it is kept, and written back with the keys the
// file had and the user set, in a stable order (the reader's, core/scene/scene_params.h); the
// keys nobody set stay out, so they keep following the defaults (and the fitting to the
// character: an absent width is scaled with an odd-sized character, a given one is not). What is
// saved reads back as the same scene.
#pragma once

#include "core/result.h"
#include "core/scene/scene.h"
#include "core/scene/scene_params.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace mfx::scene {

class SceneDocument {
public:
    // The document of scene text `text` (`where` names it in errors and is the scene's file).
    static Result<SceneDocument> fromText(const std::string& text, const std::string& where);
    static Result<SceneDocument> load(const std::filesystem::path& file);

    // A section is "character", "characters[i]", "camera", "lights[i]", "stage", "output", "post"
    // or "effects[i]".
    // Its keys: the table's entries with, in `fallback`, what the file gives (else the default).
    std::vector<ParamInfo> params(const std::string& section) const;
    // Whether the file gives `key` in `section`.
    bool given(const std::string& section, const std::string& key) const;
    // Sets `key` of `section` to `value` and reads the scene again. If the scene reader refuses the
    // result, the document is unchanged and its error is returned.
    Status set(const std::string& section, const std::string& key, const nlohmann::json& value);
    // Takes `key` out of `section` (back to its default), checked as set() is.
    Status reset(const std::string& section, const std::string& key);

    // The scene as the document reads now, and its JSON.
    const Scene& scene() const { return scene_; }
    const nlohmann::json& document() const { return doc_; }
    // The document as a file: the sections and their keys in the table's order, two-space
    // indentation, numbers and names arrays on one line.
    std::string text() const;
    // Writes text() to `file` (through a temporary file renamed over it, so a reader never sees
    // half a file); the document's file is `file` from then on.
    Status save(const std::filesystem::path& file);
    const std::string& where() const { return where_; }

private:
    SceneDocument() = default;
    // The object of `section` in `doc` (made when `create`), or null.
    static nlohmann::json* object(nlohmann::json& doc, const std::string& section, bool create);
    Status apply(nlohmann::json doc);

    std::string where_;
    nlohmann::json doc_;
    Scene scene_;
};

// parseScene in its two halves: the text's JSON (its syntax errors), then the scene it describes.
Result<nlohmann::json> parseSceneJson(const std::string& text, const std::string& where);
Result<Scene> sceneFromJson(const nlohmann::json& doc, const std::string& where);

// The table of `section` of `doc` (effect sections by their type and values).
std::vector<ParamInfo> sectionTable(const nlohmann::json& doc, const std::string& section);

} // namespace mfx::scene
