#include "core/scene/scene_document.h"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mfx::scene {

using nlohmann::json;

namespace {

// "effects[3]" -> ("effects", 3); "camera" -> ("camera", npos).
std::pair<std::string, size_t> splitSection(const std::string& section) {
    const size_t open = section.find('[');
    if (open == std::string::npos || section.back() != ']') return {section, std::string::npos};
    const std::string index = section.substr(open + 1, section.size() - open - 2);
    if (index.empty() || index.find_first_not_of("0123456789") != std::string::npos)
        return {section, std::string::npos};
    return {section.substr(0, open), size_t(std::stoul(index))};
}

const char* const kTopOrder[] = {"character", "characters", "camera", "lights",
                                 "stage",     "output",     "post",   "effects"};

// The sections that are lists of objects ("effects[2]"), and the table of a list's entries.
bool listSection(const std::string& name) {
    return name == "effects" || name == "lights" || name == "characters";
}
std::string entryTable(const std::string& list) {
    return list == "characters" ? "character" : list;
}

bool inline_(const json& v) {
    if (!v.is_array()) return !v.is_object();
    for (const json& e : v)
        if (e.is_array() || e.is_object()) return false;
    return true;
}

void write(std::ostringstream& out, const json& v, const std::vector<std::string>& order,
           const std::string& indent);

// An object's keys in `order` first, then the others in the document's order.
void writeObject(std::ostringstream& out, const json& o, const std::vector<std::string>& order,
                 const std::string& indent) {
    std::vector<std::string> keys;
    for (const std::string& k : order)
        if (o.contains(k) && std::find(keys.begin(), keys.end(), k) == keys.end())
            keys.push_back(k);
    for (auto it = o.begin(); it != o.end(); ++it)
        if (std::find(keys.begin(), keys.end(), it.key()) == keys.end()) keys.push_back(it.key());
    if (keys.empty()) {
        out << "{}";
        return;
    }
    const std::string inner = indent + "  ";
    out << "{\n";
    for (size_t i = 0; i < keys.size(); ++i) {
        out << inner << json(keys[i]).dump() << ": ";
        // The objects of an array of stops: their keys in the table's order too.
        std::vector<std::string> sub;
        const std::string prefix = keys[i] + "[].";
        for (const std::string& k : order)
            if (k.rfind(prefix, 0) == 0) sub.push_back(k.substr(prefix.size()));
        write(out, o.at(keys[i]), sub, inner);
        out << (i + 1 < keys.size() ? ",\n" : "\n");
    }
    out << indent << "}";
}

void write(std::ostringstream& out, const json& v, const std::vector<std::string>& order,
           const std::string& indent) {
    if (v.is_object()) {
        writeObject(out, v, order, indent);
    } else if (inline_(v)) {
        if (!v.is_array()) {
            out << v.dump();
            return;
        }
        out << "[";
        for (size_t i = 0; i < v.size(); ++i)
            out << (i ? ", " : "") << v[i].dump();
        out << "]";
    } else { // an array of objects or arrays, one a line
        const std::string inner = indent + "  ";
        out << "[\n";
        for (size_t i = 0; i < v.size(); ++i) {
            out << inner;
            write(out, v[i], order, inner);
            out << (i + 1 < v.size() ? ",\n" : "\n");
        }
        out << indent << "]";
    }
}

std::vector<std::string> keyOrder(const std::vector<ParamInfo>& params) {
    std::vector<std::string> order;
    for (const ParamInfo& p : params)
        order.push_back(p.key);
    return order;
}

} // namespace

// The object of `section` in `doc`, or null where the document has none.
static const json* sectionObject(const json& doc, const std::string& section) {
    const auto [name, index] = splitSection(section);
    const bool list = listSection(name);
    if (list != (index != std::string::npos)) return nullptr;
    const auto it = doc.find(name);
    if (it == doc.end()) return nullptr;
    if (!list) return &*it;
    return it->is_array() && index < it->size() ? &(*it)[index] : nullptr;
}

std::vector<ParamInfo> sectionTable(const json& doc, const std::string& section) {
    if (splitSection(section).first == "effects") {
        const json* e = sectionObject(doc, section);
        if (!e || !e->is_object() || !e->contains("type") || !(*e)["type"].is_string())
            throw std::invalid_argument("no effect " + section);
        return effectParams((*e)["type"].get<std::string>(), *e);
    }
    return sectionParams(entryTable(splitSection(section).first));
}

Result<SceneDocument> SceneDocument::fromText(const std::string& text, const std::string& where) {
    Result<json> doc = parseSceneJson(text, where);
    if (!doc) return doc.error();
    Result<Scene> scene = sceneFromJson(doc.value(), where);
    if (!scene) return scene.error();
    SceneDocument d;
    d.where_ = where;
    d.doc_ = std::move(doc).value();
    d.scene_ = std::move(scene).value();
    return d;
}

Result<SceneDocument> SceneDocument::load(const std::filesystem::path& file) {
    Result<std::string> text = readSceneText(file);
    if (!text) return text.error();
    return fromText(text.value(), file.string());
}

json* SceneDocument::object(json& doc, const std::string& section, bool create) {
    const auto [name, index] = splitSection(section);
    if (index == std::string::npos) {
        if (listSection(name)) return nullptr;
        if (!doc.contains(name)) {
            if (!create) return nullptr;
            doc[name] = json::object();
        }
        return &doc[name];
    }
    if (!listSection(name)) return nullptr;
    if (!doc.contains(name) || !doc[name].is_array() || index >= doc[name].size()) {
        if (!create || name != "lights") return nullptr;
        if (!doc.contains("lights")) doc["lights"] = json::array({json::object()});
        while (doc["lights"].size() <= index)
            doc["lights"].push_back(json::object());
    }
    return &doc[name][index];
}

std::vector<ParamInfo> SceneDocument::params(const std::string& section) const {
    std::vector<ParamInfo> table = sectionTable(doc_, section);
    if (const json* o = sectionObject(doc_, section))
        for (ParamInfo& p : table)
            if (o->contains(p.key)) p.fallback = (*o)[p.key];
    // A character's name is one of the scene's (absent: the first).
    for (ParamInfo& p : table)
        if (p.type == ParamInfo::Type::CharacterName) {
            for (const CharacterSpec& c : scene_.characters)
                p.choices.push_back(c.name);
            if (p.fallback.is_null()) p.fallback = scene_.characters.front().name;
        }
    return table;
}

bool SceneDocument::given(const std::string& section, const std::string& key) const {
    const json* o = sectionObject(doc_, section);
    return o && o->contains(key);
}

Status SceneDocument::apply(json doc) {
    Result<Scene> scene = sceneFromJson(doc, where_);
    if (!scene) return scene.error();
    doc_ = std::move(doc);
    scene_ = std::move(scene).value();
    return Ok{};
}

Status SceneDocument::set(const std::string& section, const std::string& key, const json& value) {
    json doc = doc_;
    json* o = object(doc, section, true);
    if (!o) return Error{where_ + ": no section " + section};
    const std::vector<ParamInfo> table = sectionTable(doc, section);
    const ParamInfo* p = findParam(table, key);
    if (!p) return Error{where_ + ": " + section + "." + key + ": not a key of " + section};
    (*o)[key] = value;
    return apply(std::move(doc));
}

Status SceneDocument::reset(const std::string& section, const std::string& key) {
    json doc = doc_;
    json* o = object(doc, section, false);
    if (o) o->erase(key);
    return apply(std::move(doc));
}

std::string SceneDocument::text() const {
    std::ostringstream out;
    out << "{\n";
    std::vector<std::string> present;
    for (const char* k : kTopOrder)
        if (doc_.contains(k)) present.push_back(k);
    for (size_t i = 0; i < present.size(); ++i) {
        const std::string& k = present[i];
        out << "  " << json(k).dump() << ": ";
        const json& v = doc_[k];
        if (listSection(k)) {
            if (v.empty()) {
                out << "[]";
            } else {
                out << "[\n";
                for (size_t e = 0; e < v.size(); ++e) {
                    const std::string section = k + "[" + std::to_string(e) + "]";
                    out << "    ";
                    write(out, v[e], keyOrder(sectionTable(doc_, section)), "    ");
                    out << (e + 1 < v.size() ? ",\n" : "\n");
                }
                out << "  ]";
            }
        } else {
            write(out, v, keyOrder(sectionParams(k)), "  ");
        }
        out << (i + 1 < present.size() ? ",\n" : "\n");
    }
    out << "}\n";
    return out.str();
}

Status SceneDocument::save(const std::filesystem::path& file) {
    const std::filesystem::path temporary =
        file.parent_path() / ("." + file.filename().string() + ".saving");
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out)
            return Error{temporary.string() + ": cannot write (saving " + file.string() + ")"};
        out << text();
        out.flush();
        if (!out)
            return Error{temporary.string() + ": writing failed (saving " + file.string() + ")"};
    }
    std::error_code ec;
    std::filesystem::rename(temporary, file, ec);
    if (ec) {
        std::filesystem::remove(temporary, ec);
        return Error{file.string() + ": cannot save: " + ec.message()};
    }
    where_ = file.string();
    scene_.file = where_;
    return Ok{};
}

} // namespace mfx::scene
