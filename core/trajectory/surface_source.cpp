// Xu et al., section 3.3.3: the bounding rectangle of eq. 10, the scan with a user step, the
// interpolation parameters of eqs. 11-12 (from the point's barycentric coordinates in UV space)
// and the model-space point of eq. 13.
#include "core/trajectory/surface_source.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace mfx::trajectory {

namespace {

float cross2(glm::vec2 a, glm::vec2 b) {
    return a.x * b.y - a.y * b.x;
}

// Barycentric coordinates (of B and C) of p in triangle a, b, c; `area2` is twice its signed area.
glm::vec2 barycentric(glm::vec2 p, glm::vec2 a, glm::vec2 b, glm::vec2 c, float area2) {
    const float lb = cross2(p - a, c - a) / area2;
    const float lc = cross2(b - a, p - a) / area2;
    return {lb, lc};
}

// The blend of three vertices' skin influences with weights l: each palette entry's weights
// summed, the four largest kept and renormalised.
void blendInfluences(const shared::SkinVertexIn* v[3], const float l[3], glm::uvec4& joints,
                     glm::vec4& weights) {
    std::map<uint32_t, float> sum;
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 4; ++i)
            if (v[k]->weights[i] > 0.0f) sum[v[k]->joints[i]] += l[k] * v[k]->weights[i];
    std::vector<std::pair<float, uint32_t>> order;
    for (const auto& [joint, w] : sum)
        order.emplace_back(w, joint);
    std::sort(order.begin(), order.end(), [](const auto& x, const auto& y) {
        return x.first > y.first || (x.first == y.first && x.second < y.second);
    });
    joints = glm::uvec4(0);
    weights = glm::vec4(0.0f);
    float total = 0.0f;
    for (size_t i = 0; i < std::min<size_t>(4, order.size()); ++i) {
        joints[int(i)] = order[i].second;
        weights[int(i)] = order[i].first;
        total += order[i].first;
    }
    if (total > 0.0f)
        weights /= total;
    else
        weights = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
}

constexpr int kRaster = 1024;

} // namespace

bool uvsOverlap(const anim::Mesh& mesh) {
    glm::vec2 low(INFINITY), high(-INFINITY);
    for (const anim::Primitive& primitive : mesh.primitives)
        for (const glm::vec2& uv : primitive.uvs) {
            low = glm::min(low, uv);
            high = glm::max(high, uv);
        }
    if (!(low.x <= high.x)) return false; // no UVs at all
    const glm::vec2 size = glm::max(high - low, glm::vec2(1e-12f));
    std::vector<uint8_t> coverage(size_t(kRaster) * kRaster, 0);
    size_t covered = 0, overlapping = 0;
    for (const anim::Primitive& primitive : mesh.primitives)
        for (size_t t = 0;
             primitive.uvs.size() == primitive.positions.size() && t + 2 < primitive.indices.size();
             t += 3) {
            glm::vec2 uv[3];
            for (int k = 0; k < 3; ++k)
                uv[k] =
                    (primitive.uvs[primitive.indices[t + size_t(k)]] - low) / size * float(kRaster);
            const float area2 = cross2(uv[1] - uv[0], uv[2] - uv[0]);
            if (!(std::abs(area2) > 1e-9f)) continue;
            const glm::vec2 lo = glm::min(uv[0], glm::min(uv[1], uv[2]));
            const glm::vec2 hi = glm::max(uv[0], glm::max(uv[1], uv[2]));
            for (int y = std::max(0, int(lo.y)); y <= std::min(kRaster - 1, int(hi.y)); ++y)
                for (int x = std::max(0, int(lo.x)); x <= std::min(kRaster - 1, int(hi.x)); ++x) {
                    const glm::vec2 centre(float(x) + 0.5f, float(y) + 0.5f);
                    const glm::vec2 l = barycentric(centre, uv[0], uv[1], uv[2], area2);
                    const float eps = 1e-5f; // strictly inside: shared edges are not overlaps
                    if (!(l.x > eps && l.y > eps && 1.0f - l.x - l.y > eps)) continue;
                    uint8_t& c = coverage[size_t(y) * kRaster + size_t(x)];
                    if (c == 0) ++covered;
                    if (c == 1) ++overlapping;
                    if (c < 255) ++c;
                }
        }
    // A few texels along edges may round either way; overlap is a real share of the covered area.
    return covered > 0 && double(overlapping) > 0.002 * double(covered);
}

Result<Source> selectSurfaceSource(const anim::Character& character, const Selection& selection,
                                   float step, SurfaceReport* report, size_t maxSamples) {
    if (!(step > 0.0f) || !std::isfinite(step))
        return Error{"surface step " + std::to_string(step) + " must be a finite number > 0"};
    Result<Source> selected = selectSource(character, selection);
    if (!selected) return selected.error();
    const Source& in = selected.value();
    SurfaceReport r;
    Source out;
    out.palette = in.palette;
    for (size_t t = 0; t + 2 < in.triangles.size(); t += 3) {
        const uint32_t idx[3] = {in.triangles[t], in.triangles[t + 1], in.triangles[t + 2]};
        ++r.triangles;
        glm::vec3 p[3];
        glm::vec2 uv[3];
        bool hasUv = true;
        for (int k = 0; k < 3; ++k) {
            p[k] = glm::vec3(in.vertices[idx[k]].position);
            uv[k] = in.uvs[idx[k]];
            hasUv = hasUv && std::isfinite(uv[k].x) && std::isfinite(uv[k].y);
        }
        const double modelArea = 0.5 * double(glm::length(glm::cross(p[1] - p[0], p[2] - p[0])));
        r.triangleAreas.push_back(modelArea);
        r.triangleSamples.push_back(0);
        if (!hasUv) {
            ++r.withoutUv;
            continue;
        }
        if (!(modelArea > 1e-14)) {
            ++r.degenerateInModel;
            continue;
        }
        const float area2 = cross2(uv[1] - uv[0], uv[2] - uv[0]);
        const glm::vec2 lo = glm::min(uv[0], glm::min(uv[1], uv[2])); // eq. 10
        const glm::vec2 hi = glm::max(uv[0], glm::max(uv[1], uv[2]));
        const double uvArea = 0.5 * std::abs(double(area2));
        // No area in UV: zero, or a sliver far thinner than its rectangle (collinear UVs).
        if (!(uvArea > 1e-7 * double(glm::length(hi - lo)) * double(glm::length(hi - lo))) ||
            !(uvArea > 0.0)) {
            ++r.degenerateInUv;
            continue;
        }
        // The UV step that gives one point per step² of model area on this triangle.
        const double uvStep = double(step) * std::sqrt(uvArea / modelArea);
        const double columns = std::ceil(double(hi.x - lo.x) / uvStep);
        const double rows = std::ceil(double(hi.y - lo.y) / uvStep);
        if (!(columns * rows <= 4.0 * double(maxSamples)))
            return Error{"surface step " + std::to_string(step) + " makes more than " +
                         std::to_string(maxSamples) + " points; use a larger step"};
        const shared::SkinVertexIn* corners[3] = {&in.vertices[idx[0]], &in.vertices[idx[1]],
                                                  &in.vertices[idx[2]]};
        for (int j = 0; j < int(rows); ++j)
            for (int i = 0; i < int(columns); ++i) {
                const glm::vec2 point(float(double(lo.x) + (i + 0.5) * uvStep),
                                      float(double(lo.y) + (j + 0.5) * uvStep));
                const glm::vec2 bc = barycentric(point, uv[0], uv[1], uv[2], area2);
                // Eqs. 11-12: beta is C's share, alpha B's share of what is left.
                const float beta = bc.y;
                const float alpha = beta < 1.0f ? bc.x / (1.0f - beta) : 0.0f;
                if (!(alpha >= 0.0f && alpha <= 1.0f && beta >= 0.0f && beta <= 1.0f)) continue;
                const float l[3] = {(1.0f - alpha) * (1.0f - beta), alpha * (1.0f - beta), beta};
                // Eq. 13, and the same interpolation of normals and influences.
                const glm::vec3 pm = (1.0f - alpha) * p[0] + alpha * p[1];
                const glm::vec3 pp = (1.0f - beta) * pm + beta * p[2];
                glm::vec3 n(0.0f);
                for (int k = 0; k < 3; ++k)
                    n += l[k] * glm::vec3(corners[k]->normal);
                shared::SkinVertexIn v{};
                v.position = glm::vec4(pp, 1.0f);
                v.normal =
                    glm::vec4(glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 1, 0), 0.0f);
                blendInfluences(corners, l, v.joints, v.weights);
                out.vertices.push_back(v);
                out.colours.push_back(in.colours[idx[0]]);
                out.uvs.push_back(point);
                ++r.triangleSamples.back();
                if (out.vertices.size() > maxSamples)
                    return Error{"surface step " + std::to_string(step) + " makes more than " +
                                 std::to_string(maxSamples) + " points; use a larger step"};
            }
    }
    r.samples = out.vertices.size();
    // Overlapping UVs, per selected mesh.
    std::set<std::string> names(selection.meshes.begin(), selection.meshes.end());
    for (const anim::Mesh& mesh : character.meshes) {
        if (!names.empty() && !names.count(mesh.name)) continue;
        if (uvsOverlap(mesh)) r.overlappingMeshes.push_back(mesh.name);
    }
    if (report) *report = r;
    if (out.vertices.empty())
        return Error{"the selection's surface gives no point at step " + std::to_string(step) +
                     " (" + std::to_string(r.triangles) + " triangles, " +
                     std::to_string(r.withoutUv) + " without UVs, " +
                     std::to_string(r.degenerateInUv) + " degenerate in UV)"};
    return out;
}

} // namespace mfx::trajectory
