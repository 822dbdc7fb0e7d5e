// Effect targets that travel between rigs: bone groups (right_leg, head, ...) recognised across
// the common naming conventions, glob patterns over bone names, and plain bone names.
//
// A bone's name is read as words: a namespace before the last ':' or '|' is dropped
// ("mixamorig:RightLeg"), the name is split at '_', '.', '-', spaces, lower-to-upper case changes
// and letter/digit changes ("RightUpLeg" -> right up leg, "upper_arm.R" -> upper arm r,
// "Bip01 R Calf" -> bip 01 r calf), and a leading "left"/"right" glued to a word is split off.
// The side is a word "l"/"left"/"lt" or "r"/"right"/"rt"; the part is found by looking for words
// in a fixed order: forearm/lowerarm/elbow, upper arm/arm, shoulder/clavicle, hand/wrist/palm,
// thigh/upleg/upper leg, calf/shin/knee/leg, foot/ankle, toe/ball, head, neck,
// spine/chest/pelvis/hips, and last fingers (thumb, index, middle, ring, ...). Helper bones (words
// ik, fk, mch, ctrl, pole, target, org, tweak, helper) are never recognised.
//
// A limb group is the subtree of every bone recognised as its root part, so twist bones, fingers
// and toes under it come along: right_leg = the right thigh (or upper leg) and everything below
// it; right_arm = the right upper arm and below (not the shoulder/clavicle); right_foot = the
// right foot (or ankle) and below; right_hand = the right hand (or wrist) and below; head = the
// head and below; spine = the pelvis/hips, spine, chest, torso and neck bones (no subtree: that
// would be the whole body). Where a root part is missing (a rig with no thigh bone), the next
// part down the limb is taken instead (the shin, the knee, then the foot).
#pragma once

#include "core/anim/character.h"
#include "core/result.h"

#include <string>
#include <string_view>
#include <vector>

namespace mfx::anim {

// The groups a scene may name, in the order `motionfx inspect` lists them.
const std::vector<std::string>& boneGroupNames();
bool isBoneGroup(std::string_view name);
// The four limbs, candidates for an effect that names no bone (scene fitting picks the fastest).
const std::vector<std::string>& limbGroupNames();

// The bones of `group` in `character`, in node order; empty when the rig has none recognised.
std::vector<std::string> resolveBoneGroup(const Character& character, std::string_view group);

// Whether `name` matches the glob `pattern` ('*' any run of characters, '?' one character;
// case-sensitive, like bone names).
bool globMatch(std::string_view pattern, std::string_view name);
bool isGlobPattern(std::string_view text);

// One entry of an effect's "bones": "@group" (always the group), a bone name (exact: a bone
// called "spine" wins over the spine group), a glob pattern, or a group. The
// bones it stands for, in node order, or an error naming the entry and listing the bones there
// are (and the groups, when it names neither a bone nor a group).
Result<std::vector<std::string>> resolveBoneEntry(const Character& character,
                                                  const std::string& entry);

// "name, name, ..." of every node, for error messages.
std::string listBoneNames(const Character& character);

} // namespace mfx::anim
