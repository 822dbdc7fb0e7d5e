#include "core/anim/sampling.h"

#include <algorithm>
#include <cmath>

namespace mfx::anim {

namespace {

glm::quat toQuat(const glm::vec4& v) {
    return glm::quat(v.w, v.x, v.y, v.z);
}

// Spherical interpolation the short way round; nearly parallel keys fall back to a normalised
// lerp (the slerp weights lose precision there).
glm::vec4 slerp(const glm::vec4& a, glm::vec4 b, float t) {
    float d = glm::dot(a, b);
    if (d < 0.0f) {
        b = -b;
        d = -d;
    }
    if (d > 0.9995f) return glm::normalize(a + t * (b - a));
    const float angle = std::acos(d);
    const float s = std::sin(angle);
    return glm::normalize((std::sin((1.0f - t) * angle) / s) * a + (std::sin(t * angle) / s) * b);
}

} // namespace

float clipTime(const Clip& clip, float time, Wrap wrap) {
    if (!(clip.duration > 0.0f) || !std::isfinite(time)) return 0.0f;
    if (wrap == Wrap::Clamp) return std::clamp(time, 0.0f, clip.duration);
    const float t = std::fmod(time, clip.duration);
    return t < 0.0f ? t + clip.duration : t;
}

glm::vec4 sampleChannel(const Channel& channel, float t) {
    const std::vector<float>& times = channel.times;
    const bool cubic = channel.interpolation == Interpolation::CubicSpline;
    const size_t stride = cubic ? 3 : 1;
    const size_t offset = cubic ? 1 : 0; // the value among in-tangent, value, out-tangent
    const size_t last = times.size() - 1;
    auto value = [&](size_t key) { return channel.values[key * stride + offset]; };
    if (t <= times.front()) return value(0);
    if (t >= times.back()) return value(last);
    // The key interval [k, k + 1] holding t.
    const size_t k = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
    const float dt = times[k + 1] - times[k];
    const float u = (t - times[k]) / dt;
    const bool rotation = channel.path == Path::Rotation;
    switch (channel.interpolation) {
    case Interpolation::Step:
        return value(k);
    case Interpolation::Linear:
        return rotation ? slerp(value(k), value(k + 1), u) : glm::mix(value(k), value(k + 1), u);
    case Interpolation::CubicSpline: {
        // glTF 2.0 Appendix C: Hermite spline with tangents scaled by the key interval.
        const glm::vec4 p0 = value(k), p1 = value(k + 1);
        const glm::vec4 m0 = dt * channel.values[k * 3 + 2];       // out-tangent of key k
        const glm::vec4 m1 = dt * channel.values[(k + 1) * 3 + 0]; // in-tangent of key k + 1
        const float u2 = u * u, u3 = u2 * u;
        const glm::vec4 p = (2.0f * u3 - 3.0f * u2 + 1.0f) * p0 + (u3 - 2.0f * u2 + u) * m0 +
                            (-2.0f * u3 + 3.0f * u2) * p1 + (u3 - u2) * m1;
        return rotation ? glm::normalize(p) : p;
    }
    }
    return value(k);
}

Pose samplePose(const Character& character, const Clip* clip, float time, Wrap wrap) {
    Pose pose;
    const size_t count = character.nodes.size();
    pose.local.resize(count);
    for (size_t i = 0; i < count; ++i)
        pose.local[i] = character.nodes[i].rest;
    if (clip) {
        const float t = clipTime(*clip, time, wrap);
        for (const Channel& channel : clip->channels) {
            const glm::vec4 v = sampleChannel(channel, t);
            Transform& local = pose.local[size_t(channel.node)];
            switch (channel.path) {
            case Path::Translation:
                local.translation = glm::vec3(v);
                break;
            case Path::Rotation:
                local.rotation = toQuat(v);
                break;
            case Path::Scale:
                local.scale = glm::vec3(v);
                break;
            }
        }
    }
    pose.world.resize(count);
    for (size_t i = 0; i < count; ++i) {
        const int parent = character.nodes[i].parent;
        const glm::mat4 local = pose.local[i].matrix();
        pose.world[i] = parent < 0 ? local : pose.world[size_t(parent)] * local;
    }
    return pose;
}

std::vector<glm::mat4> jointMatrices(const Character& character, int skin, const Pose& pose) {
    const Skin& s = character.skins[size_t(skin)];
    std::vector<glm::mat4> matrices(s.joints.size());
    for (size_t j = 0; j < s.joints.size(); ++j)
        matrices[j] = pose.world[size_t(s.joints[j])] * s.inverseBind[j];
    return matrices;
}

namespace {

// The world matrices of every node from the local transforms (parents come first).
void composeWorld(const Character& character, Pose& pose) {
    pose.world.resize(pose.local.size());
    for (size_t i = 0; i < pose.local.size(); ++i) {
        const int parent = character.nodes[i].parent;
        const glm::mat4 local = pose.local[i].matrix();
        pose.world[i] = parent < 0 ? local : pose.world[size_t(parent)] * local;
    }
}

// A matrix T * R * S split into its parts (a mirrored one keeps its mirror in the scale's x).
Transform split(const glm::mat4& m) {
    Transform t;
    t.translation = glm::vec3(m[3]);
    glm::vec3 scale(glm::length(glm::vec3(m[0])), glm::length(glm::vec3(m[1])),
                    glm::length(glm::vec3(m[2])));
    if (glm::determinant(glm::mat3(m)) < 0.0f) scale.x = -scale.x;
    t.scale = scale;
    const glm::vec3 x = glm::vec3(m[0]) / (scale.x != 0.0f ? scale.x : 1.0f);
    const glm::vec3 y = glm::vec3(m[1]) / (scale.y != 0.0f ? scale.y : 1.0f);
    const glm::vec3 z = glm::vec3(m[2]) / (scale.z != 0.0f ? scale.z : 1.0f);
    const glm::mat3 rotation{x, y, z};
    t.rotation = glm::normalize(glm::quat_cast(rotation));
    return t;
}

} // namespace

Pose poseFromWorld(const Character& character, std::vector<glm::mat4> world) {
    Pose pose;
    pose.local.resize(world.size());
    for (size_t i = 0; i < world.size(); ++i) {
        const int parent = character.nodes[i].parent;
        pose.local[i] =
            split(parent < 0 ? world[i] : glm::inverse(world[size_t(parent)]) * world[i]);
    }
    pose.world = std::move(world);
    return pose;
}

Pose interpolatePose(const Character& character, const Pose& a, const Pose& b, float s) {
    Pose pose;
    pose.local.resize(a.local.size());
    for (size_t i = 0; i < a.local.size(); ++i) {
        const Transform& from = a.local[i];
        const Transform& to = b.local[i];
        Transform& t = pose.local[i];
        t.translation = glm::mix(from.translation, to.translation, s);
        t.scale = glm::mix(from.scale, to.scale, s);
        const glm::quat end =
            glm::dot(from.rotation, to.rotation) < 0.0f ? -to.rotation : to.rotation;
        t.rotation = glm::normalize(glm::slerp(from.rotation, end, s));
    }
    composeWorld(character, pose);
    return pose;
}

} // namespace mfx::anim
