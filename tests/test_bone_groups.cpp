// Bone groups across rig naming conventions (Mixamo, Blender and Rigify, Unreal, 3ds Max Biped,
// the built-in fighter, FBX2glTF-style ".R" names, "L_"/"Left" prefixes), glob patterns, and the
// refusals naming the group or pattern with the bones there are.
#include "core/anim/bone_groups.h"

#include "core/anim/fighter.h"

#include <gtest/gtest.h>

namespace mfx::test {
namespace {

// A skeleton of named nodes; each entry's parent is the index of an earlier entry, or -1.
anim::Character rig(const std::vector<std::pair<std::string, int>>& nodes) {
    anim::Character c;
    for (const auto& [name, parent] : nodes)
        c.nodes.push_back({name, parent, {}});
    return c;
}

using Bones = std::vector<std::string>;

Bones group(const anim::Character& c, const std::string& name) {
    return anim::resolveBoneGroup(c, name);
}

anim::Character mixamo(const std::string& prefix) {
    return rig({{prefix + "Hips", -1},        {prefix + "Spine", 0},
                {prefix + "Spine1", 1},       {prefix + "Spine2", 2},
                {prefix + "Neck", 3},         {prefix + "Head", 4},
                {prefix + "HeadTop_End", 5},  {prefix + "RightShoulder", 3},
                {prefix + "RightArm", 7},     {prefix + "RightForeArm", 8},
                {prefix + "RightHand", 9},    {prefix + "RightHandIndex1", 10},
                {prefix + "LeftShoulder", 3}, {prefix + "LeftArm", 12},
                {prefix + "LeftForeArm", 13}, {prefix + "LeftHand", 14},
                {prefix + "RightUpLeg", 0},   {prefix + "RightLeg", 16},
                {prefix + "RightFoot", 17},   {prefix + "RightToeBase", 18},
                {prefix + "LeftUpLeg", 0},    {prefix + "LeftLeg", 20},
                {prefix + "LeftFoot", 21},    {prefix + "LeftToeBase", 22}});
}

TEST(BoneGroups, MixamoNamesWithTheirNamespace) {
    const anim::Character c = mixamo("mixamorig:");
    EXPECT_EQ(group(c, "right_leg"), (Bones{"mixamorig:RightUpLeg", "mixamorig:RightLeg",
                                            "mixamorig:RightFoot", "mixamorig:RightToeBase"}));
    EXPECT_EQ(group(c, "left_foot"), (Bones{"mixamorig:LeftFoot", "mixamorig:LeftToeBase"}));
    // The arm starts below the shoulder (clavicle) and takes the hand and fingers with it.
    EXPECT_EQ(group(c, "right_arm"), (Bones{"mixamorig:RightArm", "mixamorig:RightForeArm",
                                            "mixamorig:RightHand", "mixamorig:RightHandIndex1"}));
    EXPECT_EQ(group(c, "left_hand"), (Bones{"mixamorig:LeftHand"}));
    EXPECT_EQ(group(c, "head"), (Bones{"mixamorig:Head", "mixamorig:HeadTop_End"}));
    EXPECT_EQ(group(c, "spine"), (Bones{"mixamorig:Hips", "mixamorig:Spine", "mixamorig:Spine1",
                                        "mixamorig:Spine2", "mixamorig:Neck"}));
}

TEST(BoneGroups, MixamoNamesWithoutANamespace) {
    const anim::Character c = mixamo("");
    EXPECT_EQ(group(c, "left_leg"), (Bones{"LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase"}));
    EXPECT_EQ(group(c, "right_hand"), (Bones{"RightHand", "RightHandIndex1"}));
}

TEST(BoneGroups, BlenderAndRigifyNames) {
    const anim::Character c = rig({{"root", -1},
                                   {"DEF-spine", 0},
                                   {"DEF-spine.001", 1},
                                   {"DEF-spine.004", 2},
                                   {"DEF-spine.006", 3}, // Rigify's head has no "head" in it
                                   {"DEF-shoulder.R", 2},
                                   {"DEF-upper_arm.R", 5},
                                   {"DEF-forearm.R", 6},
                                   {"DEF-hand.R", 7},
                                   {"DEF-thigh.L", 1},
                                   {"DEF-shin.L", 9},
                                   {"DEF-foot.L", 10},
                                   {"DEF-toe.L", 11},
                                   {"MCH-thigh_ik.L", 0}, // helpers are never recognised
                                   {"ORG-thigh.L", 0}});
    EXPECT_EQ(group(c, "left_leg"),
              (Bones{"DEF-thigh.L", "DEF-shin.L", "DEF-foot.L", "DEF-toe.L"}));
    EXPECT_EQ(group(c, "right_arm"), (Bones{"DEF-upper_arm.R", "DEF-forearm.R", "DEF-hand.R"}));
    EXPECT_EQ(group(c, "right_hand"), (Bones{"DEF-hand.R"}));
    EXPECT_TRUE(group(c, "right_leg").empty());
    EXPECT_TRUE(group(c, "head").empty());
}

TEST(BoneGroups, BlenderMetarigAndCapitalisedSuffixes) {
    const anim::Character c = rig({{"spine", -1},
                                   {"thigh.R", 0},
                                   {"shin.R", 1},
                                   {"foot.R", 2},
                                   {"UpperLeg.L", 0},
                                   {"LowerLeg.L", 4},
                                   {"Foot.L", 5},
                                   {"Head", 0}});
    EXPECT_EQ(group(c, "right_leg"), (Bones{"thigh.R", "shin.R", "foot.R"}));
    EXPECT_EQ(group(c, "left_leg"), (Bones{"UpperLeg.L", "LowerLeg.L", "Foot.L"}));
    EXPECT_EQ(group(c, "left_foot"), (Bones{"Foot.L"}));
    EXPECT_EQ(group(c, "head"), (Bones{"Head"}));
}

TEST(BoneGroups, UnrealMannequinNames) {
    const anim::Character c = rig({{"root", -1},
                                   {"pelvis", 0},
                                   {"spine_01", 1},
                                   {"spine_02", 2},
                                   {"neck_01", 3},
                                   {"head", 4},
                                   {"clavicle_r", 3},
                                   {"upperarm_r", 6},
                                   {"lowerarm_r", 7},
                                   {"hand_r", 8},
                                   {"upperarm_twist_01_r", 7},
                                   {"thigh_l", 1},
                                   {"calf_l", 11},
                                   {"foot_l", 12},
                                   {"ball_l", 13},
                                   {"calf_twist_01_l", 12},
                                   {"ik_foot_l", 0}});
    EXPECT_EQ(group(c, "left_leg"),
              (Bones{"thigh_l", "calf_l", "foot_l", "ball_l", "calf_twist_01_l"}));
    EXPECT_EQ(group(c, "left_foot"), (Bones{"foot_l", "ball_l"}));
    EXPECT_EQ(group(c, "right_arm"),
              (Bones{"upperarm_r", "lowerarm_r", "hand_r", "upperarm_twist_01_r"}));
    EXPECT_EQ(group(c, "spine"), (Bones{"pelvis", "spine_01", "spine_02", "neck_01"}));
}

TEST(BoneGroups, BipedNamesWithSpacedSides) {
    const anim::Character c = rig({{"Bip01", -1},
                                   {"Bip01 Pelvis", 0},
                                   {"Bip01 Spine", 1},
                                   {"Bip01 R Clavicle", 2},
                                   {"Bip01 R UpperArm", 3},
                                   {"Bip01 R Forearm", 4},
                                   {"Bip01 R Hand", 5},
                                   {"Bip01 L Thigh", 1},
                                   {"Bip01 L Calf", 7},
                                   {"Bip01 L Foot", 8},
                                   {"Bip01 L Toe0", 9},
                                   {"Bip01 Head", 2}});
    EXPECT_EQ(group(c, "right_arm"),
              (Bones{"Bip01 R UpperArm", "Bip01 R Forearm", "Bip01 R Hand"}));
    EXPECT_EQ(group(c, "left_leg"),
              (Bones{"Bip01 L Thigh", "Bip01 L Calf", "Bip01 L Foot", "Bip01 L Toe0"}));
    EXPECT_EQ(group(c, "head"), (Bones{"Bip01 Head"}));
}

TEST(BoneGroups, SidePrefixesGluedAndSeparated) {
    const anim::Character c = rig({{"Hips", -1},
                                   {"L_Thigh", 0},
                                   {"L_Knee", 1},
                                   {"LAnkle", 2},
                                   {"RThigh", 0},
                                   {"rightleg_lower", 4},
                                   {"leftarm", 0},
                                   {"Hand_Left", 6}});
    EXPECT_EQ(group(c, "left_leg"), (Bones{"L_Thigh", "L_Knee", "LAnkle"}));
    EXPECT_EQ(group(c, "left_foot"), (Bones{"LAnkle"}));
    EXPECT_EQ(group(c, "right_leg"), (Bones{"RThigh", "rightleg_lower"}));
    EXPECT_EQ(group(c, "left_arm"), (Bones{"leftarm", "Hand_Left"}));
    EXPECT_EQ(group(c, "left_hand"), (Bones{"Hand_Left"}));
}

TEST(BoneGroups, TheBuiltInFighter) {
    const anim::Character c = anim::makeFighter();
    EXPECT_EQ(group(c, "right_leg"), (Bones{"thigh_r", "shin_r", "foot_r", "toe_r"}));
    EXPECT_EQ(group(c, "left_arm"), (Bones{"upper_arm_l", "forearm_l", "hand_l"}));
    EXPECT_EQ(group(c, "right_foot"), (Bones{"foot_r", "toe_r"}));
    EXPECT_EQ(group(c, "head"), (Bones{"head"}));
    EXPECT_EQ(group(c, "spine"), (Bones{"hips", "spine", "chest", "neck"}));
    for (const std::string& g : anim::boneGroupNames())
        EXPECT_FALSE(group(c, g).empty()) << g;
}

TEST(BoneGroups, AWholeLimbWithoutItsUpperBoneStartsLower) {
    // No thigh: the leg is the shin down.
    const anim::Character c = rig({{"pelvis", -1}, {"shin_r", 0}, {"foot_r", 1}});
    EXPECT_EQ(group(c, "right_leg"), (Bones{"shin_r", "foot_r"}));
}

TEST(BoneGroups, AnEntryIsABoneFirstThenAPatternThenAGroup) {
    // A bone literally called "head" is that bone, not the head group's subtree.
    const anim::Character c = rig({{"head", -1}, {"jaw", 0}});
    ASSERT_TRUE(anim::resolveBoneEntry(c, "head").ok());
    EXPECT_EQ(anim::resolveBoneEntry(c, "head").value(), (Bones{"head"}));
    EXPECT_EQ(group(c, "head"), (Bones{"head", "jaw"}));
}

TEST(BoneGroups, AtAlwaysMeansTheGroup) {
    const anim::Character c = anim::makeFighter();
    EXPECT_EQ(anim::resolveBoneEntry(c, "spine").value(), (Bones{"spine"}));
    EXPECT_EQ(anim::resolveBoneEntry(c, "@spine").value(),
              (Bones{"hips", "spine", "chest", "neck"}));
    const Result<Bones> unknown = anim::resolveBoneEntry(c, "@tail");
    ASSERT_FALSE(unknown.ok());
    EXPECT_NE(unknown.error().message.find("no bone group \"tail\"; groups are: right_leg"),
              std::string::npos)
        << unknown.error().message;
}

TEST(BoneGroups, FingerWordsComeLast) {
    // "Middle" names a finger in "Middle1.R" but not in "Spine_Middle".
    const anim::Character c =
        rig({{"Hips", -1}, {"Spine_Middle", 0}, {"Hand.R", 1}, {"Middle1.R", 2}});
    EXPECT_EQ(group(c, "spine"), (Bones{"Hips", "Spine_Middle"}));
    EXPECT_EQ(group(c, "right_hand"), (Bones{"Hand.R", "Middle1.R"}));
}

TEST(BoneGroups, GlobPatternsMatchBoneNames) {
    const anim::Character c = mixamo("mixamorig:");
    const Result<Bones> right = anim::resolveBoneEntry(c, "mixamorig:Right*");
    ASSERT_TRUE(right.ok()) << right.error().message;
    EXPECT_EQ(right.value().size(), 9u);
    for (const std::string& b : right.value())
        EXPECT_EQ(b.rfind("mixamorig:Right", 0), 0u) << b;
    const Result<Bones> spines = anim::resolveBoneEntry(c, "*Spine?");
    ASSERT_TRUE(spines.ok());
    EXPECT_EQ(spines.value(), (Bones{"mixamorig:Spine1", "mixamorig:Spine2"}));
    EXPECT_TRUE(anim::globMatch("a*b*c", "aXbYbZc"));
    EXPECT_FALSE(anim::globMatch("a*b*c", "aXbYbZ"));
    EXPECT_TRUE(anim::globMatch("*", ""));
    EXPECT_TRUE(anim::globMatch("*a", "*ba")); // a "*" in the name is matched by the star
    EXPECT_TRUE(anim::globMatch("*", "*"));
    EXPECT_FALSE(anim::globMatch("?", ""));
}

TEST(BoneGroups, APatternMatchingNothingIsRefusedWithTheBones) {
    const anim::Character c = rig({{"Bone", -1}, {"Bone.001", 0}});
    const Result<Bones> r = anim::resolveBoneEntry(c, "mixamorig:Right*");
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("pattern \"mixamorig:Right*\" matches no bone"),
              std::string::npos)
        << r.error().message;
    EXPECT_NE(r.error().message.find("bones are: Bone, Bone.001"), std::string::npos);
}

TEST(BoneGroups, AGroupTheRigLacksIsRefusedNamingItAndTheBones) {
    const anim::Character c = rig({{"Bone", -1}, {"Bone.001", 0}});
    const Result<Bones> r = anim::resolveBoneEntry(c, "right_leg");
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("group \"right_leg\""), std::string::npos)
        << r.error().message;
    EXPECT_NE(r.error().message.find("bones are: Bone, Bone.001"), std::string::npos);
}

TEST(BoneGroups, AnUnknownNameListsGroupsAndBones) {
    const anim::Character c = rig({{"Bone", -1}});
    const Result<Bones> r = anim::resolveBoneEntry(c, "right_tail");
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("no bone or bone group \"right_tail\""), std::string::npos)
        << r.error().message;
    EXPECT_NE(r.error().message.find("groups are: right_leg, left_leg"), std::string::npos);
    EXPECT_NE(r.error().message.find("bones are: Bone"), std::string::npos);
}

} // namespace
} // namespace mfx::test
