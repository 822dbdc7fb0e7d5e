// Index, fetch and trilinear sampling rules of the MAC grid (docs/fluid.md, "Grid access"),
// mirrored line by line in shaders/fluid/fluid_common.glsl.
#include "fluid/reference/reference_solver.h"

#include <algorithm>
#include <cmath>

namespace mfx::fluid {

namespace {
int wrap(int i, int n) {
    const int r = i % n;
    return r < 0 ? r + n : r;
}
double lerp(double a, double b, double t) {
    return a + t * (b - a);
}
} // namespace

glm::ivec3 ReferenceSolver::faceCount(int c) const {
    glm::ivec3 n = cells_;
    n[c] += 1;
    return n;
}

size_t ReferenceSolver::faceIndex(int c, glm::ivec3 q) const {
    const glm::ivec3 n = faceCount(c);
    return size_t(q.x) + size_t(n.x) * (size_t(q.y) + size_t(n.y) * size_t(q.z));
}

size_t ReferenceSolver::cellIndex(glm::ivec3 q) const {
    return size_t(q.x) + size_t(cells_.x) * (size_t(q.y) + size_t(cells_.y) * size_t(q.z));
}

double ReferenceSolver::fetchFace(int c, const Eigen::ArrayXd& field, glm::ivec3 index) const {
    const glm::ivec3 n = faceCount(c);
    bool mirror[3] = {false, false, false};
    int side[3] = {0, 0, 0};
    for (int a = 0; a < 3; ++a) {
        if (boundary(a, false) == Boundary::Periodic) {
            index[a] = wrap(index[a], cells_[a]);
        } else if (index[a] < 0) {
            index[a] = 0;
            mirror[a] = c != a && boundary(a, false) == Boundary::WallNoSlip;
            side[a] = 2 * a;
        } else if (index[a] > n[a] - 1) {
            index[a] = n[a] - 1;
            mirror[a] = c != a && boundary(a, true) == Boundary::WallNoSlip;
            side[a] = 2 * a + 1;
        }
    }
    double value = field[Eigen::Index(faceIndex(c, index))];
    for (int a = 0; a < 3; ++a)
        if (mirror[a]) value = 2.0 * double(options_.boundaries[side[a]].wallVelocity[c]) - value;
    return value;
}

glm::ivec3 ReferenceSolver::resolveCell(glm::ivec3 index) const {
    for (int a = 0; a < 3; ++a)
        index[a] = boundary(a, false) == Boundary::Periodic
                       ? wrap(index[a], cells_[a])
                       : std::clamp(index[a], 0, cells_[a] - 1);
    return index;
}

double ReferenceSolver::fetchCell(const Eigen::ArrayXd& field, glm::ivec3 index, int channels,
                                  int channel) const {
    return field[Eigen::Index(cellIndex(resolveCell(index)) * size_t(channels) + size_t(channel))];
}

double ReferenceSolver::sampleFace(int c, const Eigen::ArrayXd& field, glm::dvec3 x) const {
    glm::dvec3 g = x / h_ - 0.5;
    g[c] += 0.5;
    const glm::dvec3 base = glm::floor(g);
    const glm::dvec3 f = g - base;
    const glm::ivec3 i0(base);
    auto at = [&](int dx, int dy, int dz) {
        return fetchFace(c, field, i0 + glm::ivec3(dx, dy, dz));
    };
    const double c00 = lerp(at(0, 0, 0), at(1, 0, 0), f.x);
    const double c10 = lerp(at(0, 1, 0), at(1, 1, 0), f.x);
    const double c01 = lerp(at(0, 0, 1), at(1, 0, 1), f.x);
    const double c11 = lerp(at(0, 1, 1), at(1, 1, 1), f.x);
    return lerp(lerp(c00, c10, f.y), lerp(c01, c11, f.y), f.z);
}

double ReferenceSolver::sampleCell(const Eigen::ArrayXd& field, glm::dvec3 x, int channels,
                                   int channel) const {
    const glm::dvec3 g = x / h_ - 0.5;
    const glm::dvec3 base = glm::floor(g);
    const glm::dvec3 f = g - base;
    const glm::ivec3 i0(base);
    auto at = [&](int dx, int dy, int dz) {
        return fetchCell(field, i0 + glm::ivec3(dx, dy, dz), channels, channel);
    };
    const double c00 = lerp(at(0, 0, 0), at(1, 0, 0), f.x);
    const double c10 = lerp(at(0, 1, 0), at(1, 1, 0), f.x);
    const double c01 = lerp(at(0, 0, 1), at(1, 0, 1), f.x);
    const double c11 = lerp(at(0, 1, 1), at(1, 1, 1), f.x);
    return lerp(lerp(c00, c10, f.y), lerp(c01, c11, f.y), f.z);
}

glm::dvec2 ReferenceSolver::sampleFaceRange(int c, const Eigen::ArrayXd& field,
                                            glm::dvec3 x) const {
    glm::dvec3 g = x / h_ - 0.5;
    g[c] += 0.5;
    const glm::ivec3 i0(glm::floor(g));
    glm::dvec2 range(1e300, -1e300);
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                const double v = fetchFace(c, field, i0 + glm::ivec3(dx, dy, dz));
                range = {std::min(range.x, v), std::max(range.y, v)};
            }
    return range;
}

glm::dvec2 ReferenceSolver::sampleCellRange(const Eigen::ArrayXd& field, glm::dvec3 x, int channels,
                                            int channel) const {
    const glm::ivec3 i0(glm::floor(x / h_ - 0.5));
    glm::dvec2 range(1e300, -1e300);
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                const double v = fetchCell(field, i0 + glm::ivec3(dx, dy, dz), channels, channel);
                range = {std::min(range.x, v), std::max(range.y, v)};
            }
    return range;
}

glm::dvec3 ReferenceSolver::velocityAt(glm::dvec3 x) const {
    return {sampleFace(0, velocity_[0], x), sampleFace(1, velocity_[1], x),
            sampleFace(2, velocity_[2], x)};
}

glm::dvec3 ReferenceSolver::clampToDomain(glm::dvec3 x) const {
    for (int a = 0; a < 3; ++a) {
        const double length = double(cells_[a]) * h_;
        if (boundary(a, false) == Boundary::Periodic)
            x[a] = x[a] - length * std::floor(x[a] / length);
        else
            x[a] = std::clamp(x[a], 0.0, length);
    }
    return x;
}

glm::dvec3 ReferenceSolver::backTrace(glm::dvec3 x) const {
    return backTrace(x, dt());
}

glm::dvec3 ReferenceSolver::backTrace(glm::dvec3 x, double interval) const {
    const glm::dvec3 v = velocityAt(x);
    if (options_.integrator == Integrator::Euler) return clampToDomain(x - interval * v);
    const glm::dvec3 mid = clampToDomain(x - 0.5 * interval * v);
    return clampToDomain(x - interval * velocityAt(mid));
}

glm::dvec3 ReferenceSolver::facePosition(int c, glm::ivec3 index) const {
    glm::dvec3 x = (glm::dvec3(index) + 0.5) * h_;
    x[c] -= 0.5 * h_;
    return x;
}

glm::dvec3 ReferenceSolver::cellCentre(glm::ivec3 index) const {
    return (glm::dvec3(index) + 0.5) * h_;
}

bool ReferenceSolver::wallNormalFace(int c, glm::ivec3 index) const {
    auto isWall = [](Boundary b) {
        return b == Boundary::WallFreeSlip || b == Boundary::WallNoSlip;
    };
    return (index[c] == 0 && isWall(boundary(c, false))) ||
           (index[c] == cells_[c] && isWall(boundary(c, true)));
}

} // namespace mfx::fluid
