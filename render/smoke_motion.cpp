#include "render/smoke_motion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace mfx::render {

namespace {

// A grid's cell-centred velocity and pigment alpha, for trilinear samples.
struct CellFields {
    fluid::GridShape shape;
    glm::vec3 origin{0.0f};
    std::vector<glm::vec4> cells; // velocity xyz, alpha

    explicit CellFields(const SmokeFields& grid) : shape(grid.state->grid), origin(grid.origin) {
        const fluid::FieldState& s = *grid.state;
        const std::vector<float>* faces[3] = {&s.velocityX, &s.velocityY, &s.velocityZ};
        cells.resize(size_t(shape.cellCount()));
        for (uint32_t k = 0; k < shape.cellsZ; ++k)
            for (uint32_t j = 0; j < shape.cellsY; ++j)
                for (uint32_t i = 0; i < shape.cellsX; ++i) {
                    glm::vec4 v(0.0f);
                    for (int c = 0; c < 3; ++c) {
                        const glm::uvec3 n = fluid::faceExtent(shape, c);
                        glm::uvec3 hi(i, j, k);
                        hi[c] += 1;
                        v[c] = 0.5f * ((*faces[c])[i + n.x * (j + size_t(n.y) * k)] +
                                       (*faces[c])[hi.x + n.x * (hi.y + size_t(n.y) * hi.z)]);
                    }
                    const size_t cell = size_t(shape.index(i, j, k));
                    v.w = s.pigment[4 * cell + 3];
                    for (int c = 0; c < 4; ++c)
                        if (!std::isfinite(v[c])) v[c] = 0.0f;
                    cells[cell] = v;
                }
    }

    // Trilinear sample at world position p (clamped to the cell centres).
    glm::vec4 sample(glm::vec3 p) const {
        const glm::vec3 g = (p - origin) / shape.cellSize - 0.5f;
        const glm::vec3 hi(float(shape.cellsX - 1), float(shape.cellsY - 1),
                           float(shape.cellsZ - 1));
        const glm::vec3 c = glm::clamp(g, glm::vec3(0.0f), hi);
        const glm::uvec3 i0(c);
        const glm::uvec3 i1 = glm::min(i0 + 1u, glm::uvec3(hi));
        const glm::vec3 f = c - glm::vec3(i0);
        glm::vec4 out(0.0f);
        for (int corner = 0; corner < 8; ++corner) {
            const glm::uvec3 at((corner & 1) ? i1.x : i0.x, (corner & 2) ? i1.y : i0.y,
                                (corner & 4) ? i1.z : i0.z);
            const float w = ((corner & 1) ? f.x : 1.0f - f.x) * ((corner & 2) ? f.y : 1.0f - f.y) *
                            ((corner & 4) ? f.z : 1.0f - f.z);
            out += w * cells[size_t(shape.index(at.x, at.y, at.z))];
        }
        return out;
    }
};

// Where the ray eye + t dir is inside [lo, hi]: t in [near, far], empty when near >= far.
glm::vec2 crossBox(glm::vec3 eye, glm::vec3 dir, glm::vec3 lo, glm::vec3 hi) {
    float near = 0.0f, far = std::numeric_limits<float>::max();
    for (int a = 0; a < 3; ++a) {
        if (std::abs(dir[a]) < 1e-12f) {
            if (eye[a] < lo[a] || eye[a] > hi[a]) return {1.0f, 0.0f};
            continue;
        }
        float t0 = (lo[a] - eye[a]) / dir[a], t1 = (hi[a] - eye[a]) / dir[a];
        if (t0 > t1) std::swap(t0, t1);
        near = std::max(near, t0);
        far = std::min(far, t1);
    }
    return {near, far};
}

} // namespace

MotionField projectedSmokeMotion(std::span<const SmokeFields> grids, const SceneCamera& camera,
                                 uint32_t width, uint32_t height, float seconds,
                                 float densityScale) {
    MotionField field(width, height);
    std::vector<CellFields> fields;
    for (const SmokeFields& g : grids)
        if (g.state) fields.emplace_back(g);
    const glm::mat4 inverse = glm::inverse(camera.viewProjection);
    auto toPixel = [&](glm::vec3 p) {
        const glm::vec4 clip = camera.viewProjection * glm::vec4(p, 1.0f);
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        return glm::vec2((ndc.x + 1.0f) * 0.5f * float(width),
                         (1.0f - ndc.y) * 0.5f * float(height));
    };
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const glm::vec2 ndc(2.0f * (float(x) + 0.5f) / float(width) - 1.0f,
                                1.0f - 2.0f * (float(y) + 0.5f) / float(height));
            const glm::vec4 nearPoint = inverse * glm::vec4(ndc, 0.0f, 1.0f);
            const glm::vec4 farPoint = inverse * glm::vec4(ndc, 1.0f, 1.0f);
            const glm::vec3 a = glm::vec3(nearPoint) / nearPoint.w;
            const glm::vec3 dir = glm::normalize(glm::vec3(farPoint) / farPoint.w - a);
            glm::vec2 motion(0.0f);
            float weight = 0.0f;
            for (const CellFields& f : fields) {
                const glm::vec3 lo = f.origin;
                const glm::vec3 hi =
                    lo +
                    f.shape.cellSize * glm::vec3(f.shape.cellsX, f.shape.cellsY, f.shape.cellsZ);
                const glm::vec2 span = crossBox(a, dir, lo, hi);
                if (span.x >= span.y) continue;
                const float step = f.shape.cellSize;
                float transmittance = 1.0f;
                for (float t = span.x + 0.5f * step; t < span.y && transmittance > 0.01f;
                     t += step) {
                    const glm::vec3 p = a + t * dir;
                    const glm::vec4 s = f.sample(p);
                    const float density = std::max(s.w, 0.0f) * densityScale;
                    if (density <= 1e-5f) continue;
                    const float opacity = 1.0f - std::exp(-density * step);
                    const float w = transmittance * opacity;
                    motion += w * (toPixel(p + glm::vec3(s) * seconds) - toPixel(p));
                    weight += w;
                    transmittance *= 1.0f - opacity;
                }
            }
            if (weight > 1e-6f) {
                field.xy[(size_t(y) * width + x) * 2] = motion.x / weight;
                field.xy[(size_t(y) * width + x) * 2 + 1] = motion.y / weight;
            }
        }
    return field;
}

} // namespace mfx::render
