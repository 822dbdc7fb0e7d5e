#include "core/anim/fighter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <string>
#include <tuple>

namespace mfx::anim {

namespace {

constexpr float kPi = 3.14159265358979f;

float radians(float degrees) {
    return degrees * kPi / 180.0f;
}

// --- Skeleton -----------------------------------------------------------------------------------

struct JointSpec {
    const char* name;
    const char* parent;
    glm::vec3 offset; // from the parent joint, bind pose (T-pose, arms along +-x)
};

// Left is +x (the fighter faces +z).
const JointSpec kJoints[] = {
    {"hips", nullptr, {0.0f, 0.98f, 0.0f}},
    {"spine", "hips", {0.0f, 0.12f, 0.0f}},
    {"chest", "spine", {0.0f, 0.18f, 0.0f}},
    {"neck", "chest", {0.0f, 0.22f, 0.0f}},
    {"head", "neck", {0.0f, 0.09f, 0.0f}},
    {"shoulder_l", "chest", {0.07f, 0.17f, 0.0f}},
    {"upper_arm_l", "shoulder_l", {0.11f, 0.0f, 0.0f}},
    {"forearm_l", "upper_arm_l", {0.28f, 0.0f, 0.0f}},
    {"hand_l", "forearm_l", {0.25f, 0.0f, 0.0f}},
    {"shoulder_r", "chest", {-0.07f, 0.17f, 0.0f}},
    {"upper_arm_r", "shoulder_r", {-0.11f, 0.0f, 0.0f}},
    {"forearm_r", "upper_arm_r", {-0.28f, 0.0f, 0.0f}},
    {"hand_r", "forearm_r", {-0.25f, 0.0f, 0.0f}},
    {"thigh_l", "hips", {0.1f, -0.05f, 0.0f}},
    {"shin_l", "thigh_l", {0.0f, -0.42f, 0.0f}},
    {"foot_l", "shin_l", {0.0f, -0.42f, 0.0f}},
    {"toe_l", "foot_l", {0.0f, -0.05f, 0.13f}},
    {"thigh_r", "hips", {-0.1f, -0.05f, 0.0f}},
    {"shin_r", "thigh_r", {0.0f, -0.42f, 0.0f}},
    {"foot_r", "shin_r", {0.0f, -0.42f, 0.0f}},
    {"toe_r", "foot_r", {0.0f, -0.05f, 0.13f}},
};
constexpr int kJointCount = int(std::size(kJoints));

int jointIndex(const char* name) {
    for (int i = 0; i < kJointCount; ++i)
        if (std::string_view(kJoints[i].name) == name) return i;
    return -1;
}

// Bind-pose world position of every joint.
std::array<glm::vec3, kJointCount> bindPositions() {
    std::array<glm::vec3, kJointCount> p{};
    for (int i = 0; i < kJointCount; ++i) {
        const int parent = kJoints[i].parent ? jointIndex(kJoints[i].parent) : -1;
        p[size_t(i)] = (parent < 0 ? glm::vec3(0.0f) : p[size_t(parent)]) + kJoints[i].offset;
    }
    return p;
}

// --- Mesh ---------------------------------------------------------------------------------------

// A closed tube from `from` to `to` (radius profile r0 -> r1, rounded ends), skinned to `joint`
// with a smooth hand-over to `startJoint` near the start and `endJoint` near the end. Its UVs
// fill the atlas cell `cell` of an 8 x 4 grid, so that no two parts overlap.
struct TubeSpec {
    int joint;
    int startJoint; // -1: none
    int endJoint;   // -1: none
    glm::vec3 from, to;
    float r0, r1;
    int cell;
};

constexpr int kAround = 16;
constexpr int kAlong = 12;
constexpr int kAtlasColumns = 8;
constexpr int kAtlasRows = 4;

void addTube(Primitive& p, const TubeSpec& t) {
    const uint32_t base = uint32_t(p.positions.size());
    const glm::vec3 axis = t.to - t.from;
    const glm::vec3 dir = glm::normalize(axis);
    // Any frame around the axis.
    const glm::vec3 helper = std::abs(dir.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 side = glm::normalize(glm::cross(dir, helper));
    const glm::vec3 up = glm::cross(side, dir);
    const glm::vec2 cellOrigin(float(t.cell % kAtlasColumns) / kAtlasColumns,
                               float(t.cell / kAtlasColumns) / kAtlasRows);
    const glm::vec2 cellSize(1.0f / kAtlasColumns, 1.0f / kAtlasRows);
    const float margin = 0.05f; // of a cell, so neighbouring parts never touch
    for (int j = 0; j <= kAlong; ++j) {
        const float s = float(j) / kAlong;
        // Rounded ends: the radius closes like a capsule over the first and last eighths.
        const float end = std::min(s, 1.0f - s) * 8.0f;
        const float round = end >= 1.0f ? 1.0f : std::sqrt(std::max(0.0f, end * (2.0f - end)));
        const float r = glm::mix(t.r0, t.r1, s) * round;
        const glm::vec3 centre = t.from + s * axis;
        // Weights: the tube's joint, handing over to the neighbours within 25% of either end.
        float wStart = t.startJoint >= 0 ? 0.5f * std::clamp(1.0f - s / 0.25f, 0.0f, 1.0f) : 0.0f;
        float wEnd = t.endJoint >= 0 ? 0.5f * std::clamp((s - 0.75f) / 0.25f, 0.0f, 1.0f) : 0.0f;
        for (int i = 0; i <= kAround; ++i) {
            const float a = 2.0f * kPi * float(i % kAround) / kAround;
            const glm::vec3 radial = std::cos(a) * side + std::sin(a) * up;
            p.positions.push_back(centre + r * radial);
            const glm::vec2 uv(float(i) / kAround, s);
            p.uvs.push_back(cellOrigin + cellSize * (margin + (1.0f - 2.0f * margin) * uv));
            glm::uvec4 joints(uint32_t(t.joint), 0, 0, 0);
            glm::vec4 weights(1.0f - wStart - wEnd, 0.0f, 0.0f, 0.0f);
            if (wStart > 0.0f) {
                joints[1] = uint32_t(t.startJoint);
                weights[1] = wStart;
            }
            if (wEnd > 0.0f) {
                joints[2] = uint32_t(t.endJoint);
                weights[2] = wEnd;
            }
            p.joints.push_back(joints);
            p.weights.push_back(weights);
        }
    }
    const uint32_t row = kAround + 1;
    for (uint32_t j = 0; j < uint32_t(kAlong); ++j)
        for (uint32_t i = 0; i < uint32_t(kAround); ++i) {
            const uint32_t a = base + j * row + i, b = a + 1, c = a + row, d = c + 1;
            p.indices.insert(p.indices.end(), {a, c, b, b, c, d});
        }
}

// Smooth normals where vertices at the same position (a tube's UV seam, its closed ends) share
// one normal, so no shading seam shows.
std::vector<glm::vec3> weldedNormals(const std::vector<glm::vec3>& positions,
                                     const std::vector<uint32_t>& indices) {
    std::vector<glm::vec3> normals = smoothNormals(positions, indices, glm::vec3(0, 1, 0));
    std::map<std::tuple<float, float, float>, glm::vec3> sum;
    for (size_t v = 0; v < positions.size(); ++v)
        sum[{positions[v].x, positions[v].y, positions[v].z}] += normals[v];
    for (size_t v = 0; v < positions.size(); ++v) {
        const glm::vec3 n = sum[{positions[v].x, positions[v].y, positions[v].z}];
        if (glm::length(n) > 1e-6f) normals[v] = glm::normalize(n);
    }
    return normals;
}

Primitive makePrimitive(const std::vector<TubeSpec>& tubes, glm::vec4 color) {
    Primitive p;
    p.skin = 0;
    p.baseColor = color;
    for (const TubeSpec& t : tubes)
        addTube(p, t);
    p.normals = weldedNormals(p.positions, p.indices);
    return p;
}

Mesh makeBody() {
    const auto at = bindPositions();
    auto j = [](const char* name) { return jointIndex(name); };
    auto pos = [&](const char* name) { return at[size_t(jointIndex(name))]; };
    int cell = 0;
    auto tube = [&](const char* joint, const char* start, const char* end, glm::vec3 from,
                    glm::vec3 to, float r0, float r1) {
        return TubeSpec{j(joint), start ? j(start) : -1, end ? j(end) : -1, from, to, r0, r1,
                        cell++};
    };
    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    std::vector<TubeSpec> top, pants, skin, shoes, belt;
    // Gi top: torso and sleeves.
    top.push_back(
        tube("spine", "hips", "chest", pos("hips") + 0.02f * down, pos("chest"), 0.15f, 0.16f));
    top.push_back(tube("chest", "spine", "neck", pos("chest") - glm::vec3(0, 0.03f, 0),
                       pos("neck") - glm::vec3(0, 0.02f, 0), 0.17f, 0.13f));
    for (const char* s : {"l", "r"}) {
        const std::string side(s);
        top.push_back(tube(("shoulder_" + side).c_str(), "chest", ("upper_arm_" + side).c_str(),
                           pos(("shoulder_" + side).c_str()) * glm::vec3(0.5f, 1, 1),
                           pos(("upper_arm_" + side).c_str()), 0.065f, 0.06f));
        top.push_back(tube(("upper_arm_" + side).c_str(), ("shoulder_" + side).c_str(),
                           ("forearm_" + side).c_str(), pos(("upper_arm_" + side).c_str()),
                           pos(("forearm_" + side).c_str()), 0.058f, 0.05f));
        top.push_back(tube(("forearm_" + side).c_str(), ("upper_arm_" + side).c_str(),
                           ("hand_" + side).c_str(), pos(("forearm_" + side).c_str()),
                           pos(("hand_" + side).c_str()), 0.05f, 0.042f));
        const glm::vec3 out =
            glm::normalize(pos(("hand_" + side).c_str()) - pos(("forearm_" + side).c_str()));
        skin.push_back(tube(("hand_" + side).c_str(), ("forearm_" + side).c_str(), nullptr,
                            pos(("hand_" + side).c_str()) - 0.01f * out,
                            pos(("hand_" + side).c_str()) + 0.11f * out, 0.045f, 0.04f));
        pants.push_back(tube(("thigh_" + side).c_str(), "hips", ("shin_" + side).c_str(),
                             pos(("thigh_" + side).c_str()) + glm::vec3(0, 0.06f, 0),
                             pos(("shin_" + side).c_str()), 0.095f, 0.07f));
        pants.push_back(tube(("shin_" + side).c_str(), ("thigh_" + side).c_str(),
                             ("foot_" + side).c_str(), pos(("shin_" + side).c_str()),
                             pos(("foot_" + side).c_str()), 0.065f, 0.05f));
        shoes.push_back(
            tube(("foot_" + side).c_str(), ("shin_" + side).c_str(), ("toe_" + side).c_str(),
                 pos(("foot_" + side).c_str()) + glm::vec3(0, -0.03f, -0.06f),
                 pos(("toe_" + side).c_str()) + glm::vec3(0, 0.0f, 0.04f), 0.055f, 0.045f));
    }
    belt.push_back(tube("hips", nullptr, "spine", pos("hips") + glm::vec3(0, -0.06f, 0),
                        pos("hips") + glm::vec3(0, 0.06f, 0), 0.16f, 0.16f));
    skin.push_back(tube("neck", "chest", "head", pos("neck") - glm::vec3(0, 0.03f, 0), pos("head"),
                        0.055f, 0.05f));
    skin.push_back(tube("head", "neck", nullptr, pos("head") - glm::vec3(0, 0.02f, 0),
                        pos("head") + glm::vec3(0, 0.24f, 0.0f), 0.1f, 0.095f));

    Mesh body;
    body.name = "body";
    body.primitives.push_back(makePrimitive(top, {0.85f, 0.12f, 0.1f, 1.0f}));    // red gi
    body.primitives.push_back(makePrimitive(pants, {0.08f, 0.08f, 0.12f, 1.0f})); // dark pants
    body.primitives.push_back(makePrimitive(skin, {0.87f, 0.66f, 0.52f, 1.0f}));  // skin
    body.primitives.push_back(makePrimitive(shoes, {0.95f, 0.95f, 0.9f, 1.0f}));  // white shoes
    body.primitives.push_back(makePrimitive(belt, {0.95f, 0.75f, 0.1f, 1.0f}));   // gold belt
    return body;
}

Mesh makeSword() {
    const auto at = bindPositions();
    const int hand = jointIndex("hand_r");
    const glm::vec3 grip = at[size_t(hand)] + glm::vec3(-0.07f, 0.0f, 0.0f);
    // Held in the right fist, blade along +z in the bind pose (pointing forward).
    std::vector<TubeSpec> hilt = {{hand, -1, -1, grip + glm::vec3(0, 0, -0.12f),
                                   grip + glm::vec3(0, 0, 0.06f), 0.018f, 0.018f, 24},
                                  {hand, -1, -1, grip + glm::vec3(-0.09f, 0, 0.07f),
                                   grip + glm::vec3(0.09f, 0, 0.07f), 0.016f, 0.016f, 25}};
    std::vector<TubeSpec> blade = {{hand, -1, -1, grip + glm::vec3(0, 0, 0.07f),
                                    grip + glm::vec3(0, 0, 0.95f), 0.028f, 0.012f, 26}};
    Mesh sword;
    sword.name = "sword";
    sword.primitives.push_back(makePrimitive(hilt, {0.3f, 0.18f, 0.08f, 1.0f}));
    sword.primitives.push_back(makePrimitive(blade, {0.82f, 0.86f, 0.92f, 1.0f}));
    // A flat blade: squash the tube across its width.
    for (glm::vec3& p : sword.primitives[1].positions)
        p.y = grip.y + 0.25f * (p.y - grip.y);
    sword.primitives[1].normals =
        weldedNormals(sword.primitives[1].positions, sword.primitives[1].indices);
    return sword;
}

// --- Clips --------------------------------------------------------------------------------------

// Euler angles in degrees (applied z, then y, then x... as the quaternion product X * Y * Z).
glm::quat euler(float x, float y, float z) {
    return glm::angleAxis(radians(x), glm::vec3(1, 0, 0)) *
           glm::angleAxis(radians(y), glm::vec3(0, 1, 0)) *
           glm::angleAxis(radians(z), glm::vec3(0, 0, 1));
}

struct Key {
    float time;
    glm::quat rotation;
};

class ClipBuilder {
public:
    explicit ClipBuilder(std::string name) { clip_.name = std::move(name); }

    ClipBuilder& rotate(const char* joint, std::vector<Key> keys) {
        Channel c;
        c.node = jointIndex(joint);
        c.path = Path::Rotation;
        glm::quat previous(1, 0, 0, 0);
        for (const Key& k : keys) {
            glm::quat q = glm::normalize(k.rotation);
            if (glm::dot(q, previous) < 0.0f) q = -q; // keep neighbouring keys on one side
            previous = q;
            c.times.push_back(k.time);
            c.values.push_back({q.x, q.y, q.z, q.w});
        }
        clip_.channels.push_back(std::move(c));
        return *this;
    }
    ClipBuilder& translateHips(std::vector<std::pair<float, glm::vec3>> keys) {
        Channel c;
        c.node = jointIndex("hips");
        c.path = Path::Translation;
        for (const auto& [t, offset] : keys) {
            c.times.push_back(t);
            c.values.push_back(glm::vec4(kJoints[0].offset + offset, 0.0f));
        }
        clip_.channels.push_back(std::move(c));
        return *this;
    }
    Clip build() {
        for (const Channel& c : clip_.channels)
            clip_.duration = std::max(clip_.duration, c.times.back());
        return clip_;
    }

private:
    Clip clip_;
};

// The fighting stance every clip starts and ends in: knees bent, fists up.
struct Stance {
    glm::quat upperArmL = euler(0, -20, -70), forearmL = euler(0, -110, 0);
    glm::quat upperArmR = euler(0, 20, 70), forearmR = euler(0, 110, 0);
    glm::quat thighL = euler(-20, 0, 0), shinL = euler(35, 0, 0), footL = euler(-15, 0, 0);
    glm::quat thighR = euler(-20, 0, 0), shinR = euler(35, 0, 0), footR = euler(-15, 0, 0);
    glm::vec3 hips{0.0f, -0.06f, 0.0f};
};

Clip idle() {
    const Stance s;
    return ClipBuilder("idle")
        .translateHips({{0.0f, s.hips}, {0.6f, s.hips + glm::vec3(0, -0.015f, 0)}, {1.2f, s.hips}})
        .rotate("chest", {{0.0f, euler(0, 0, 0)}, {0.6f, euler(4, 0, 0)}, {1.2f, euler(0, 0, 0)}})
        .rotate("upper_arm_l", {{0.0f, s.upperArmL}, {1.2f, s.upperArmL}})
        .rotate("forearm_l", {{0.0f, s.forearmL}, {1.2f, s.forearmL}})
        .rotate("upper_arm_r", {{0.0f, s.upperArmR}, {1.2f, s.upperArmR}})
        .rotate("forearm_r", {{0.0f, s.forearmR}, {1.2f, s.forearmR}})
        .rotate("thigh_l", {{0.0f, s.thighL}, {1.2f, s.thighL}})
        .rotate("shin_l", {{0.0f, s.shinL}, {1.2f, s.shinL}})
        .rotate("foot_l", {{0.0f, s.footL}, {1.2f, s.footL}})
        .rotate("thigh_r", {{0.0f, s.thighR}, {1.2f, s.thighR}})
        .rotate("shin_r", {{0.0f, s.shinR}, {1.2f, s.shinR}})
        .rotate("foot_r", {{0.0f, s.footR}, {1.2f, s.footR}})
        .build();
}

// Anticipation (0-0.25 s: weight onto the left leg, right knee chambered), the strike (0.25-0.4:
// hips turn, the right leg swings round and extends), follow-through and recovery (0.4-0.9).
Clip roundhouseKick() {
    const Stance s;
    return ClipBuilder("roundhouse_kick")
        .translateHips({{0.0f, s.hips},
                        {0.25f, s.hips + glm::vec3(0.04f, 0.02f, 0)},
                        {0.4f, s.hips + glm::vec3(0.05f, 0.05f, 0.02f)},
                        {0.9f, s.hips}})
        .rotate("hips", {{0.0f, euler(0, 0, 0)},
                         {0.25f, euler(0, 20, 0)},
                         {0.4f, euler(0, -80, 15)},
                         {0.55f, euler(0, -100, 10)},
                         {0.9f, euler(0, 0, 0)}})
        .rotate("chest", {{0.0f, euler(0, 0, 0)},
                          {0.25f, euler(0, -15, 0)},
                          {0.4f, euler(0, 40, -15)},
                          {0.9f, euler(0, 0, 0)}})
        .rotate("thigh_r", {{0.0f, s.thighR},
                            {0.25f, euler(-80, 0, 20)},
                            {0.4f, euler(-85, 0, 80)},
                            {0.55f, euler(-70, 0, 60)},
                            {0.9f, s.thighR}})
        .rotate("shin_r", {{0.0f, s.shinR},
                           {0.25f, euler(120, 0, 0)},
                           {0.4f, euler(5, 0, 0)},
                           {0.55f, euler(60, 0, 0)},
                           {0.9f, s.shinR}})
        .rotate("foot_r", {{0.0f, s.footR}, {0.4f, euler(40, 0, 0)}, {0.9f, s.footR}})
        .rotate("thigh_l", {{0.0f, s.thighL}, {0.4f, euler(-5, 0, 0)}, {0.9f, s.thighL}})
        .rotate("shin_l", {{0.0f, s.shinL}, {0.4f, euler(10, 0, 0)}, {0.9f, s.shinL}})
        .rotate("upper_arm_l",
                {{0.0f, s.upperArmL}, {0.4f, euler(0, 20, -50)}, {0.9f, s.upperArmL}})
        .rotate("forearm_l", {{0.0f, s.forearmL}, {0.9f, s.forearmL}})
        .rotate("upper_arm_r", {{0.0f, s.upperArmR}, {0.4f, euler(20, 0, 40)}, {0.9f, s.upperArmR}})
        .rotate("forearm_r", {{0.0f, s.forearmR}, {0.9f, s.forearmR}})
        .build();
}

// Chamber (0-0.12 s), a fast extension of the right arm (0.12-0.2), hold and retract (0.2-0.5).
Clip straightPunch() {
    const Stance s;
    return ClipBuilder("straight_punch")
        .translateHips({{0.0f, s.hips}, {0.2f, s.hips + glm::vec3(0, 0, 0.06f)}, {0.5f, s.hips}})
        .rotate("hips", {{0.0f, euler(0, 0, 0)},
                         {0.12f, euler(0, -10, 0)},
                         {0.2f, euler(0, 25, 0)},
                         {0.5f, euler(0, 0, 0)}})
        .rotate("chest", {{0.0f, euler(0, 0, 0)}, {0.2f, euler(0, 20, 0)}, {0.5f, euler(0, 0, 0)}})
        .rotate("upper_arm_r", {{0.0f, s.upperArmR},
                                {0.12f, euler(0, 30, 75)},
                                {0.2f, euler(0, 85, 5)},
                                {0.3f, euler(0, 85, 5)},
                                {0.5f, s.upperArmR}})
        .rotate("forearm_r", {{0.0f, s.forearmR},
                              {0.12f, euler(0, 130, 0)},
                              {0.2f, euler(0, 2, 0)},
                              {0.3f, euler(0, 2, 0)},
                              {0.5f, s.forearmR}})
        .rotate("upper_arm_l", {{0.0f, s.upperArmL}, {0.5f, s.upperArmL}})
        .rotate("forearm_l", {{0.0f, s.forearmL}, {0.5f, s.forearmL}})
        .rotate("thigh_l", {{0.0f, s.thighL}, {0.5f, s.thighL}})
        .rotate("shin_l", {{0.0f, s.shinL}, {0.5f, s.shinL}})
        .rotate("thigh_r", {{0.0f, s.thighR}, {0.5f, s.thighR}})
        .rotate("shin_r", {{0.0f, s.shinR}, {0.5f, s.shinR}})
        .build();
}

// Struck from the front: the blow's jolt (0-0.08 s: hips knocked back and down, spine, chest and
// head thrown back and turned, arms flung open, knees buckling), held a moment (0.08-0.25), then
// the recovery to the stance (0.25-0.75).
Clip hitReaction() {
    const Stance s;
    return ClipBuilder("hit_react")
        .translateHips({{0.0f, s.hips},
                        {0.08f, s.hips + glm::vec3(0.0f, -0.05f, -0.12f)},
                        {0.25f, s.hips + glm::vec3(0.0f, -0.06f, -0.14f)},
                        {0.75f, s.hips}})
        .rotate("hips", {{0.0f, euler(0, 0, 0)},
                         {0.08f, euler(8, 12, 0)},
                         {0.25f, euler(6, 10, 0)},
                         {0.75f, euler(0, 0, 0)}})
        .rotate("spine", {{0.0f, euler(0, 0, 0)},
                          {0.08f, euler(-18, 8, -4)},
                          {0.25f, euler(-14, 6, -3)},
                          {0.75f, euler(0, 0, 0)}})
        .rotate("chest", {{0.0f, euler(0, 0, 0)},
                          {0.08f, euler(-22, 14, -8)},
                          {0.25f, euler(-16, 10, -6)},
                          {0.75f, euler(0, 0, 0)}})
        .rotate("neck", {{0.0f, euler(0, 0, 0)},
                         {0.08f, euler(-30, -12, 6)},
                         {0.25f, euler(-18, -8, 4)},
                         {0.75f, euler(0, 0, 0)}})
        .rotate("upper_arm_l", {{0.0f, s.upperArmL},
                                {0.08f, euler(0, -60, -25)},
                                {0.25f, euler(0, -50, -35)},
                                {0.75f, s.upperArmL}})
        .rotate("forearm_l", {{0.0f, s.forearmL},
                              {0.08f, euler(0, -40, 0)},
                              {0.25f, euler(0, -60, 0)},
                              {0.75f, s.forearmL}})
        .rotate("upper_arm_r", {{0.0f, s.upperArmR},
                                {0.08f, euler(0, 60, 25)},
                                {0.25f, euler(0, 50, 35)},
                                {0.75f, s.upperArmR}})
        .rotate("forearm_r", {{0.0f, s.forearmR},
                              {0.08f, euler(0, 40, 0)},
                              {0.25f, euler(0, 60, 0)},
                              {0.75f, s.forearmR}})
        .rotate("thigh_l", {{0.0f, s.thighL},
                            {0.08f, euler(-35, 0, 0)},
                            {0.25f, euler(-38, 0, 0)},
                            {0.75f, s.thighL}})
        .rotate(
            "shin_l",
            {{0.0f, s.shinL}, {0.08f, euler(55, 0, 0)}, {0.25f, euler(60, 0, 0)}, {0.75f, s.shinL}})
        .rotate("foot_l", {{0.0f, s.footL}, {0.08f, euler(-20, 0, 0)}, {0.75f, s.footL}})
        .rotate("thigh_r", {{0.0f, s.thighR},
                            {0.08f, euler(-30, 0, 0)},
                            {0.25f, euler(-34, 0, 0)},
                            {0.75f, s.thighR}})
        .rotate(
            "shin_r",
            {{0.0f, s.shinR}, {0.08f, euler(50, 0, 0)}, {0.25f, euler(56, 0, 0)}, {0.75f, s.shinR}})
        .rotate("foot_r", {{0.0f, s.footR}, {0.08f, euler(-20, 0, 0)}, {0.75f, s.footR}})
        .build();
}

// Wind-up over the right shoulder (0-0.3 s), a diagonal cut down across the body (0.3-0.42),
// follow-through low left and recovery (0.42-0.8).
Clip swordSlash() {
    const Stance s;
    return ClipBuilder("sword_slash")
        .translateHips(
            {{0.0f, s.hips}, {0.42f, s.hips + glm::vec3(0, -0.05f, 0.08f)}, {0.8f, s.hips}})
        .rotate("hips", {{0.0f, euler(0, 0, 0)},
                         {0.3f, euler(0, -30, 0)},
                         {0.42f, euler(0, 35, 0)},
                         {0.8f, euler(0, 0, 0)}})
        .rotate("chest", {{0.0f, euler(0, 0, 0)},
                          {0.3f, euler(-10, -25, 0)},
                          {0.42f, euler(15, 30, 0)},
                          {0.8f, euler(0, 0, 0)}})
        .rotate("upper_arm_r", {{0.0f, s.upperArmR},
                                {0.3f, euler(0, -20, -60)},
                                {0.42f, euler(0, 70, 60)},
                                {0.55f, euler(0, 80, 80)},
                                {0.8f, s.upperArmR}})
        .rotate("forearm_r", {{0.0f, s.forearmR},
                              {0.3f, euler(0, 100, 0)},
                              {0.42f, euler(0, 10, 0)},
                              {0.8f, s.forearmR}})
        .rotate("hand_r", {{0.0f, euler(0, 0, 0)},
                           {0.3f, euler(0, 0, 40)},
                           {0.42f, euler(0, 0, -30)},
                           {0.8f, euler(0, 0, 0)}})
        .rotate("upper_arm_l", {{0.0f, s.upperArmL}, {0.8f, s.upperArmL}})
        .rotate("forearm_l", {{0.0f, s.forearmL}, {0.8f, s.forearmL}})
        .rotate("thigh_l", {{0.0f, s.thighL}, {0.42f, euler(-45, 0, 0)}, {0.8f, s.thighL}})
        .rotate("shin_l", {{0.0f, s.shinL}, {0.42f, euler(60, 0, 0)}, {0.8f, s.shinL}})
        .rotate("thigh_r", {{0.0f, s.thighR}, {0.42f, euler(10, 0, 0)}, {0.8f, s.thighR}})
        .rotate("shin_r", {{0.0f, s.shinR}, {0.42f, euler(30, 0, 0)}, {0.8f, s.shinR}})
        .build();
}

// A full turn on the spot with the arms flung out: slow start, fast middle, settle.
Clip spin() {
    const Stance s;
    ClipBuilder b("spin");
    b.translateHips({{0.0f, s.hips}, {0.4f, s.hips + glm::vec3(0, 0.04f, 0)}, {0.8f, s.hips}});
    std::vector<Key> turn;
    const float times[] = {0.0f, 0.15f, 0.3f, 0.45f, 0.6f, 0.8f};
    const float angles[] = {0.0f, -30.0f, -140.0f, -250.0f, -330.0f, -360.0f};
    for (int i = 0; i < 6; ++i)
        turn.push_back({times[i], euler(0, angles[i], 0)});
    b.rotate("hips", turn);
    b.rotate("upper_arm_l", {{0.0f, s.upperArmL}, {0.3f, euler(0, 0, -10)}, {0.8f, s.upperArmL}});
    b.rotate("forearm_l", {{0.0f, s.forearmL}, {0.3f, euler(0, -10, 0)}, {0.8f, s.forearmL}});
    b.rotate("upper_arm_r", {{0.0f, s.upperArmR}, {0.3f, euler(0, 0, 10)}, {0.8f, s.upperArmR}});
    b.rotate("forearm_r", {{0.0f, s.forearmR}, {0.3f, euler(0, 10, 0)}, {0.8f, s.forearmR}});
    b.rotate("thigh_l", {{0.0f, s.thighL}, {0.8f, s.thighL}});
    b.rotate("shin_l", {{0.0f, s.shinL}, {0.8f, s.shinL}});
    b.rotate("thigh_r", {{0.0f, s.thighR}, {0.3f, euler(-40, 0, 0)}, {0.8f, s.thighR}});
    b.rotate("shin_r", {{0.0f, s.shinR}, {0.3f, euler(70, 0, 0)}, {0.8f, s.shinR}});
    return b.build();
}

// Clips played one after another, each from where the one before ended (every clip starts and
// ends in the stance, so they join without a jump): per channel, the keys of each clip that has
// it, shifted by the durations before it; the first key of a clip that repeats the last one (the
// stance at the seam) is dropped. A channel a clip lacks holds its last key through it (and one a
// first clip lacks holds its first: sampling clamps).
Clip sequence(const std::string& name, const std::vector<Clip>& clips) {
    Clip out;
    out.name = name;
    float start = 0.0f;
    for (const Clip& clip : clips) {
        for (const Channel& c : clip.channels) {
            auto same =
                std::find_if(out.channels.begin(), out.channels.end(), [&](const Channel& o) {
                    return o.node == c.node && o.path == c.path;
                });
            if (same == out.channels.end()) {
                Channel fresh;
                fresh.node = c.node;
                fresh.path = c.path;
                fresh.interpolation = c.interpolation;
                same = out.channels.insert(out.channels.end(), fresh);
            }
            for (size_t k = 0; k < c.times.size(); ++k) {
                const float t = start + c.times[k];
                if (!same->times.empty() && t <= same->times.back()) continue; // the seam's repeat
                same->times.push_back(t);
                same->values.push_back(c.values[k]);
            }
        }
        start += clip.duration;
    }
    out.duration = start;
    return out;
}

} // namespace

Character makeFighter() {
    Character c;
    c.name = "fighter";
    const auto at = bindPositions();
    Skin skin;
    skin.name = "fighter";
    for (int i = 0; i < kJointCount; ++i) {
        Node node;
        node.name = kJoints[i].name;
        node.parent = kJoints[i].parent ? jointIndex(kJoints[i].parent) : -1;
        node.rest.translation = kJoints[i].offset;
        c.nodes.push_back(node);
        skin.joints.push_back(i);
        skin.inverseBind.push_back(glm::translate(glm::mat4(1.0f), -at[size_t(i)]));
    }
    c.skins.push_back(skin);
    c.meshes.push_back(makeBody());
    c.meshes.push_back(makeSword());
    c.clips = {idle(), roundhouseKick(), straightPunch(), swordSlash(), spin(), hitReaction()};
    c.clips.push_back(sequence("kick_slash", {roundhouseKick(), swordSlash()}));
    return c;
}

} // namespace mfx::anim
