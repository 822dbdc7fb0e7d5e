#include "core/anim/bone_groups.h"

#include <algorithm>
#include <cctype>
#include <set>

namespace mfx::anim {

namespace {

enum class Side { None, Left, Right };
enum class Part {
    None,
    Spine, // pelvis, hips, spine, chest, torso
    Neck,
    Head,
    Shoulder, // clavicle: not part of the arm group
    UpperArm,
    ForeArm,
    Hand,
    Finger,
    UpperLeg,
    LowerLeg,
    Foot,
    Toe,
};

struct Reading {
    Side side = Side::None;
    Part part = Part::None;
};

bool isLower(char c) {
    return std::islower(static_cast<unsigned char>(c)) != 0;
}
bool isUpper(char c) {
    return std::isupper(static_cast<unsigned char>(c)) != 0;
}
bool isDigit(char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
}
bool isAlpha(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) != 0;
}

// The words of a bone name (see the header), lower case.
std::vector<std::string> words(std::string_view name) {
    const size_t namespaceEnd = name.find_last_of(":|");
    if (namespaceEnd != std::string_view::npos) name = name.substr(namespaceEnd + 1);
    std::vector<std::string> out;
    std::string word;
    auto flush = [&] {
        if (word.empty()) return;
        for (const char* side : {"left", "right"}) { // "leftarm" -> left arm
            const std::string prefix = side;
            if (word.size() > prefix.size() && word.compare(0, prefix.size(), prefix) == 0 &&
                isAlpha(word[prefix.size()])) {
                out.push_back(prefix);
                word = word.substr(prefix.size());
            }
        }
        out.push_back(word);
        word.clear();
    };
    for (size_t i = 0; i < name.size(); ++i) {
        const char c = name[i];
        if (!isAlpha(c) && !isDigit(c)) {
            flush();
            continue;
        }
        if (!word.empty()) {
            const char previous = name[i - 1];
            const bool lowerToUpper = isUpper(c) && (isLower(previous) || isDigit(previous));
            // "LThigh": a capital run ends before a capital that starts a lower-case word.
            const bool acronymEnd =
                isUpper(c) && isUpper(previous) && i + 1 < name.size() && isLower(name[i + 1]);
            const bool digitChange = isDigit(c) != isDigit(previous);
            if (lowerToUpper || acronymEnd || digitChange) flush();
        }
        word += char(std::tolower(static_cast<unsigned char>(c)));
    }
    flush();
    return out;
}

Reading read(std::string_view name) {
    const std::vector<std::string> w = words(name);
    const std::set<std::string> has(w.begin(), w.end());
    auto any = [&](std::initializer_list<const char*> list) {
        return std::any_of(list.begin(), list.end(), [&](const char* s) { return has.count(s); });
    };
    Reading r;
    if (any({"ik", "fk", "mch", "ctrl", "control", "pole", "target", "org", "tweak", "helper"}))
        return r; // rig controls and helpers move nothing themselves
    if (any({"l", "left", "lt"})) r.side = Side::Left;
    if (any({"r", "right", "rt"})) r.side = r.side == Side::Left ? Side::None : Side::Right;
    const bool upper = any({"upper", "up"});
    const bool lower = any({"lower", "low", "fore"});
    if (any({"forearm", "lowerarm", "elbow", "radius", "ulna"}) || (has.count("arm") && lower))
        r.part = Part::ForeArm;
    else if (any({"upperarm", "uparm", "humerus", "arm"}))
        r.part = Part::UpperArm;
    else if (any({"shoulder", "clavicle", "clav", "collar"}))
        r.part = Part::Shoulder;
    else if (any({"hand", "wrist", "palm"}))
        r.part = Part::Hand;
    else if (any({"thigh", "upleg", "upperleg", "femur"}) || (has.count("leg") && upper) ||
             (has.count("hip") && r.side != Side::None))
        r.part = Part::UpperLeg;
    else if (any({"calf", "shin", "knee", "tibia", "lowerleg", "leg"}))
        r.part = Part::LowerLeg;
    else if (any({"foot", "ankle"}))
        r.part = Part::Foot;
    else if (any({"toe", "toes", "toebase", "ball"}))
        r.part = Part::Toe;
    else if (has.count("head"))
        r.part = Part::Head;
    else if (has.count("neck"))
        r.part = Part::Neck;
    else if (any({"spine", "chest", "upperchest", "torso", "abdomen", "pelvis", "waist", "hips",
                  "hip", "belly"}))
        r.part = Part::Spine;
    else if (any({"thumb", "index", "middle", "ring", "pinky", "little", "finger", "fingers"}))
        r.part = Part::Finger; // last: "middle" and "ring" also name other things
    return r;
}

struct Group {
    const char* name;
    Side side;
    std::vector<std::vector<Part>> roots; // the first list that finds a bone is the group's root
    bool subtree;
};

const std::vector<Group>& groups() {
    static const std::vector<Group> table = {
        {"right_leg", Side::Right, {{Part::UpperLeg}, {Part::LowerLeg}, {Part::Foot}}, true},
        {"left_leg", Side::Left, {{Part::UpperLeg}, {Part::LowerLeg}, {Part::Foot}}, true},
        {"right_arm", Side::Right, {{Part::UpperArm}, {Part::ForeArm}, {Part::Hand}}, true},
        {"left_arm", Side::Left, {{Part::UpperArm}, {Part::ForeArm}, {Part::Hand}}, true},
        {"right_hand", Side::Right, {{Part::Hand}, {Part::Finger}}, true},
        {"left_hand", Side::Left, {{Part::Hand}, {Part::Finger}}, true},
        {"right_foot", Side::Right, {{Part::Foot}, {Part::Toe}}, true},
        {"left_foot", Side::Left, {{Part::Foot}, {Part::Toe}}, true},
        {"head", Side::None, {{Part::Head}}, true},
        {"spine", Side::None, {{Part::Spine, Part::Neck}}, false},
    };
    return table;
}

} // namespace

const std::vector<std::string>& boneGroupNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const Group& g : groups())
            out.push_back(g.name);
        return out;
    }();
    return names;
}

bool isBoneGroup(std::string_view name) {
    const auto& names = boneGroupNames();
    return std::find(names.begin(), names.end(), name) != names.end();
}

const std::vector<std::string>& limbGroupNames() {
    static const std::vector<std::string> names = {"right_leg", "left_leg", "right_arm",
                                                   "left_arm"};
    return names;
}

std::vector<std::string> resolveBoneGroup(const Character& character, std::string_view name) {
    const auto group = std::find_if(groups().begin(), groups().end(),
                                    [&](const Group& g) { return name == g.name; });
    if (group == groups().end()) return {};
    const size_t count = character.nodes.size();
    std::vector<Reading> readings(count);
    for (size_t i = 0; i < count; ++i)
        readings[i] = read(character.nodes[i].name);
    std::vector<bool> in(count, false);
    for (const std::vector<Part>& parts : group->roots) {
        bool found = false;
        for (size_t i = 0; i < count; ++i)
            if (readings[i].side == group->side &&
                std::find(parts.begin(), parts.end(), readings[i].part) != parts.end()) {
                in[i] = true;
                found = true;
            }
        if (found) break;
    }
    if (group->subtree) // parents come first: one pass takes every descendant
        for (size_t i = 0; i < count; ++i)
            if (character.nodes[i].parent >= 0 && in[size_t(character.nodes[i].parent)])
                in[i] = true;
    std::vector<std::string> out; // names, once each (a mesh node may share its bone's name)
    for (size_t i = 0; i < count; ++i)
        if (in[i] && std::find(out.begin(), out.end(), character.nodes[i].name) == out.end())
            out.push_back(character.nodes[i].name);
    return out;
}

bool globMatch(std::string_view pattern, std::string_view name) {
    // Iterative matching with one backtrack point: the last '*' seen.
    size_t p = 0, n = 0, star = std::string_view::npos, resume = 0;
    while (n < name.size()) {
        if (p < pattern.size() && pattern[p] == '*') { // before the literal test: "*" in a name
            star = p++;
            resume = n;
        } else if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == name[n])) {
            ++p;
            ++n;
        } else if (star != std::string_view::npos) {
            p = star + 1;
            n = ++resume;
        } else {
            return false;
        }
    }
    while (p < pattern.size() && pattern[p] == '*')
        ++p;
    return p == pattern.size();
}

bool isGlobPattern(std::string_view text) {
    return text.find_first_of("*?") != std::string_view::npos;
}

std::string listBoneNames(const Character& character) {
    std::string out;
    for (const Node& n : character.nodes)
        out += (out.empty() ? "" : ", ") + n.name;
    return out;
}

namespace {

std::string groupList() {
    std::string out;
    for (const std::string& g : boneGroupNames())
        out += (out.empty() ? "" : ", ") + g;
    return out;
}

// The bones of a known group, or the refusal naming it and the bones there are.
Result<std::vector<std::string>> groupBones(const Character& character, const std::string& group) {
    std::vector<std::string> out = resolveBoneGroup(character, group);
    if (out.empty())
        return Error{"group \"" + group +
                     "\": no bone of this rig is recognised as one (README.md \"Your own "
                     "character\"); name its bones instead; bones are: " +
                     listBoneNames(character)};
    return out;
}

} // namespace

Result<std::vector<std::string>> resolveBoneEntry(const Character& character,
                                                  const std::string& entry) {
    if (entry.size() > 1 && entry[0] == '@') { // "@spine": the group, even where a bone is "spine"
        const std::string group = entry.substr(1);
        if (!isBoneGroup(group))
            return Error{"no bone group \"" + group + "\"; groups are: " + groupList()};
        return groupBones(character, group);
    }
    if (character.findNode(entry)) return std::vector<std::string>{entry};
    if (isGlobPattern(entry)) {
        std::vector<std::string> out;
        for (const Node& n : character.nodes)
            if (globMatch(entry, n.name)) out.push_back(n.name);
        if (out.empty())
            return Error{"pattern \"" + entry +
                         "\" matches no bone; bones are: " + listBoneNames(character)};
        return out;
    }
    if (isBoneGroup(entry)) return groupBones(character, entry);
    return Error{"no bone or bone group \"" + entry + "\"; groups are: " + groupList() +
                 "; bones are: " + listBoneNames(character)};
}

} // namespace mfx::anim
