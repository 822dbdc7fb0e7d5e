// Twin of shaders/core/trajectory_segment.glsl; keep the order of operations the same.
#include "core/trajectory/build_segment.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace mfx::trajectory {

namespace {

// The shader's arithmetic (shaders/core/dual_quat.glsl), spelled the same way: quaternions as
// (x, y, z, w) vectors, rotation by two cross products.
glm::vec4 asVec4(const glm::quat& q) {
    return {q.x, q.y, q.z, q.w};
}

glm::vec4 quatMul(const glm::vec4& a, const glm::vec4& b) {
    const glm::vec3 av(a), bv(b);
    return glm::vec4(a.w * bv + b.w * av + glm::cross(av, bv), a.w * b.w - glm::dot(av, bv));
}

glm::vec3 quatRotate(const glm::vec4& q, const glm::vec3& v) {
    const glm::vec3 u(q);
    const glm::vec3 uv = glm::cross(u, v);
    const glm::vec3 uuv = glm::cross(u, uv);
    return v + ((uv * q.w) + uuv) * 2.0f;
}

glm::vec3 transformPoint(const anim::DualQuatJoint& t, const glm::vec3& p) {
    const glm::vec4 real = asVec4(t.rigid.real);
    const glm::vec4 conjugate(-real.x, -real.y, -real.z, real.w);
    const glm::vec3 translation = 2.0f * glm::vec3(quatMul(asVec4(t.rigid.dual), conjugate));
    return quatRotate(real, t.scale * p) + translation;
}

glm::vec3 transformNormal(const anim::DualQuatJoint& t, const glm::vec3& n) {
    return glm::normalize(quatRotate(asVec4(t.rigid.real), n / t.scale));
}

} // namespace

Status checkParameters(const SegmentParameters& p) {
    if (p.subSamples < 1 || p.subSamples > MFX_TRAJECTORY_MAX_SUBSAMPLES)
        return Error{"sub_samples " + std::to_string(p.subSamples) + " is outside 1.." +
                     std::to_string(MFX_TRAJECTORY_MAX_SUBSAMPLES)};
    if (!std::isfinite(p.impulseScale))
        return Error{"impulse coefficient k must be a finite number"};
    if (!(p.alphaStart >= 0.0f && p.alphaStart <= 1.0f))
        return Error{"alpha at tau = 0 must be in [0, 1]"};
    if (!(p.alphaEnd >= 0.0f && p.alphaEnd <= 1.0f))
        return Error{"alpha at tau = 1 must be in [0, 1]"};
    if (!(p.alphaPower > 0.0f && std::isfinite(p.alphaPower)))
        return Error{"attenuation power must be a finite number > 0"};
    return Ok{};
}

float attenuation(float tau, const SegmentParameters& p) {
    const float shaped = tau > 0.0f ? std::pow(tau, p.alphaPower) : 0.0f;
    return p.alphaStart + (p.alphaEnd - p.alphaStart) * shaped;
}

anim::DualQuatJoint interpolateTransform(const anim::DualQuatJoint& a, const anim::DualQuatJoint& b,
                                         float tau) {
    const float s = glm::dot(a.rigid.real, b.rigid.real) < 0.0f ? -tau : tau;
    const glm::quat real = (1.0f - tau) * a.rigid.real + s * b.rigid.real;
    const glm::quat dual = (1.0f - tau) * a.rigid.dual + s * b.rigid.dual;
    const glm::vec3 scale = (1.0f - tau) * a.scale + tau * b.scale;
    const float length = glm::length(real);
    return {{real / length, dual / length}, scale};
}

std::vector<anim::DualQuatJoint> vertexTransforms(const Source& source,
                                                  const std::vector<anim::DualQuatJoint>& palette) {
    std::vector<anim::DualQuatJoint> out;
    out.reserve(source.vertices.size());
    for (const shared::SkinVertexIn& v : source.vertices) {
        glm::vec4 weights = v.weights;
        for (int k = 0; k < 4; ++k)
            if (v.joints[k] >= palette.size()) weights[k] = 0.0f; // as the shader drops them
        glm::uvec4 joints = v.joints;
        for (int k = 0; k < 4; ++k)
            if (joints[k] >= palette.size()) joints[k] = 0;
        out.push_back(anim::blendJoints(palette, joints, weights));
    }
    return out;
}

std::vector<shared::TrajectoryVertex> buildSegment(const Source& source,
                                                   const std::vector<anim::DualQuatJoint>& now,
                                                   const std::vector<anim::DualQuatJoint>& previous,
                                                   float time, float dt,
                                                   const SegmentParameters& parameters) {
    const uint32_t s =
        std::clamp(parameters.subSamples, 1u, uint32_t(MFX_TRAJECTORY_MAX_SUBSAMPLES));
    std::vector<shared::TrajectoryVertex> out(source.vertices.size() * (s + 1));
    std::vector<glm::vec3> positions(s + 1), normals(s + 1);
    const float perStep = dt > 0.0f ? float(s) / dt : 0.0f;
    for (size_t v = 0; v < source.vertices.size(); ++v) {
        const shared::SkinVertexIn& in = source.vertices[v];
        for (uint32_t i = 0; i <= s; ++i) {
            const float tau = float(i) / float(s);
            const anim::DualQuatJoint t = interpolateTransform(now[v], previous[v], tau);
            positions[i] = transformPoint(t, glm::vec3(in.position));
            normals[i] = transformNormal(t, glm::vec3(in.normal));
        }
        for (uint32_t i = 0; i <= s; ++i) {
            const float tau = float(i) / float(s);
            glm::vec3 velocity;
            if (i == 0)
                velocity = (positions[0] - positions[1]) * perStep;
            else if (i == s)
                velocity = (positions[s - 1] - positions[s]) * perStep;
            else
                velocity = 0.5f * ((positions[i - 1] - positions[i]) * perStep +
                                   (positions[i] - positions[i + 1]) * perStep);
            shared::TrajectoryVertex& o = out[v * (s + 1) + i];
            o.position = glm::vec4(positions[i], tau);
            o.normal = glm::vec4(normals[i], time - tau * dt);
            const glm::vec4& colour = source.colours[v];
            o.color = glm::vec4(glm::vec3(colour), colour.a * attenuation(tau, parameters));
            o.velocity = glm::vec4(velocity * parameters.impulseScale, time);
        }
    }
    return out;
}

} // namespace mfx::trajectory
