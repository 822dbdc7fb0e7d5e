#include "core/anim/body_capsules.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace mfx::anim {

namespace {

// The unit eigenvector of the symmetric matrix `m` with the largest eigenvalue, by power
// iteration from the axis with the largest diagonal entry; +x for a zero matrix.
glm::vec3 principalAxis(const glm::dmat3& m) {
    int start = 0;
    for (int i = 1; i < 3; ++i)
        if (m[i][i] > m[start][start]) start = i;
    glm::dvec3 v(0.0);
    v[start] = 1.0;
    for (int iteration = 0; iteration < 64; ++iteration) {
        const glm::dvec3 next = m * v;
        const double length = glm::length(next);
        if (!(length > 1e-30)) break;
        v = next / length;
    }
    return glm::vec3(v);
}

BodyCapsule fit(int node, const std::vector<glm::vec3>& points, float radiusQuantile) {
    BodyCapsule capsule;
    capsule.node = node;
    capsule.vertices = uint32_t(points.size());
    glm::dvec3 mean(0.0);
    for (const glm::vec3& p : points)
        mean += glm::dvec3(p);
    mean /= double(points.size());
    glm::dmat3 covariance(0.0);
    for (const glm::vec3& p : points) {
        const glm::dvec3 d = glm::dvec3(p) - mean;
        covariance += glm::outerProduct(d, d);
    }
    const glm::vec3 axis = principalAxis(covariance);
    std::vector<float> along, distances;
    along.reserve(points.size());
    distances.reserve(points.size());
    for (const glm::vec3& p : points) {
        const glm::vec3 d = p - glm::vec3(mean);
        const float t = glm::dot(d, axis);
        along.push_back(t);
        distances.push_back(glm::length(d - t * axis));
    }
    std::vector<float> sorted = distances;
    const size_t k = std::min(sorted.size() - 1,
                              size_t(std::ceil(double(radiusQuantile) * double(sorted.size())) -
                                     (radiusQuantile > 0.0f ? 1.0 : 0.0)));
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
    const float r = sorted[k];
    capsule.radius = r;
    // The shortest axis whose round caps still hold every point within the radius: a point at
    // (t, d) lies in the cap of an end at s when |t - s| <= sqrt(r² - d²).
    float low = 1e30f, high = -1e30f;
    for (size_t i = 0; i < points.size(); ++i) {
        if (distances[i] > r) continue;
        const float reach = std::sqrt(std::max(r * r - distances[i] * distances[i], 0.0f));
        low = std::min(low, along[i] + reach);
        high = std::max(high, along[i] - reach);
    }
    const glm::vec3 centre(mean);
    if (high < low) { // every point fits one sphere about the middle of the two
        capsule.a = capsule.b = centre + 0.5f * (low + high) * axis;
    } else {
        capsule.a = centre + low * axis;
        capsule.b = centre + high * axis;
    }
    return capsule;
}

} // namespace

std::vector<BodyCapsule> fitBodyCapsules(const Character& character, float radiusQuantile) {
    radiusQuantile = std::clamp(std::isfinite(radiusQuantile) ? radiusQuantile : 1.0f, 0.0f, 1.0f);
    std::map<int, std::vector<glm::vec3>> byNode; // node order: the same capsules every time
    for (const Mesh& mesh : character.meshes)
        for (const Primitive& primitive : mesh.primitives) {
            if (primitive.skin >= 0 && !primitive.joints.empty()) {
                const Skin& skin = character.skins[size_t(primitive.skin)];
                for (size_t v = 0; v < primitive.positions.size(); ++v) {
                    const glm::vec4 w = primitive.weights[v];
                    int best = 0;
                    for (int i = 1; i < 4; ++i)
                        if (w[i] > w[best]) best = i;
                    const uint32_t joint = primitive.joints[v][best];
                    const glm::vec4 local =
                        skin.inverseBind[joint] * glm::vec4(primitive.positions[v], 1.0f);
                    byNode[skin.joints[joint]].push_back(glm::vec3(local) / local.w);
                }
            } else if (primitive.node >= 0) {
                std::vector<glm::vec3>& points = byNode[primitive.node];
                points.insert(points.end(), primitive.positions.begin(), primitive.positions.end());
            }
        }
    std::vector<BodyCapsule> capsules;
    for (const auto& [node, points] : byNode)
        if (!points.empty()) capsules.push_back(fit(node, points, radiusQuantile));
    return capsules;
}

PosedCapsule poseCapsule(const BodyCapsule& capsule, const Pose& pose) {
    const glm::mat4& world = pose.world[size_t(capsule.node)];
    const float scale = std::cbrt(std::abs(glm::determinant(glm::mat3(world))));
    return {glm::vec3(world * glm::vec4(capsule.a, 1.0f)),
            glm::vec3(world * glm::vec4(capsule.b, 1.0f)), capsule.radius * scale};
}

float signedDistance(const PosedCapsule& capsule, glm::vec3 p) {
    const glm::vec3 ab = capsule.b - capsule.a;
    const float length2 = glm::dot(ab, ab);
    const float t =
        length2 > 0.0f ? std::clamp(glm::dot(p - capsule.a, ab) / length2, 0.0f, 1.0f) : 0.0f;
    return glm::length(p - (capsule.a + t * ab)) - capsule.radius;
}

} // namespace mfx::anim
