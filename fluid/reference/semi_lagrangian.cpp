// The advection schemes' building blocks (docs/fluid.md, steps 2-3 and "Accuracy options"): the
// departure points of a field's sample points, one semi-Lagrangian pass (Stam 1999, eq. 7: the
// value found by tracing back through the velocity and sampling trilinearly), and the limiter of
// Selle, Fedkiw, Kim, Liu, Rossignac, "An Unconditionally Stable MacCormack Method" (J. Sci.
// Comput. 2008): a corrected value is clamped to the smallest and largest of the values the
// semi-Lagrangian sample at its departure point interpolates from. (Selle et al. also describe
// reverting to the semi-Lagrangian value instead; clamping keeps more of the correction.)
// advectField picks the scheme of options().advection for one field.
#include "fluid/reference/reference_solver.h"

#include <algorithm>

namespace mfx::fluid {

namespace {
// Calls visit(point, index) for every sample point of a field with `n` points per axis, in the
// order of its array (x fastest).
template <typename Visit>
void forEachPoint(glm::ivec3 n, Visit visit) {
    size_t point = 0;
    for (int k = 0; k < n.z; ++k)
        for (int j = 0; j < n.y; ++j)
            for (int i = 0; i < n.x; ++i)
                visit(point++, glm::ivec3(i, j, k));
}
} // namespace

Eigen::ArrayXd ReferenceSolver::advectField(int field, const Eigen::ArrayXd& source) const {
    switch (options_.advection) {
    case AdvectionScheme::SemiLagrangian:
        break;
    case AdvectionScheme::MacCormack:
        return advectMacCormack(field, source);
    case AdvectionScheme::Bfecc:
        return advectBfecc(field, source);
    }
    return semiLagrangian(field, source, departurePoints(field, dt()));
}

std::vector<glm::dvec3> ReferenceSolver::departurePoints(int field, double interval) const {
    const glm::ivec3 n = field == kPigmentField ? cells_ : faceCount(field);
    std::vector<glm::dvec3> points(size_t(n.x) * size_t(n.y) * size_t(n.z));
    forEachPoint(n, [&](size_t point, glm::ivec3 q) {
        if (field == kPigmentField)
            points[point] = backTrace(cellCentre(q), interval);
        else if (!wallNormalFace(field, q)) // a wall-normal face is never sampled for
            points[point] = backTrace(facePosition(field, q), interval);
    });
    return points;
}

Eigen::ArrayXd ReferenceSolver::semiLagrangian(int field, const Eigen::ArrayXd& source,
                                               std::span<const glm::dvec3> departures) const {
    Eigen::ArrayXd result(source.size());
    if (field == kPigmentField) {
        forEachPoint(cells_, [&](size_t point, glm::ivec3) {
            for (int channel = 0; channel < 4; ++channel)
                result[Eigen::Index(point * 4 + size_t(channel))] =
                    sampleCellOutsideSolids(source, departures[point], 4, channel);
        });
    } else {
        forEachPoint(faceCount(field), [&](size_t point, glm::ivec3 q) {
            result[Eigen::Index(point)] =
                wallNormalFace(field, q) ? 0.0 : sampleFace(field, source, departures[point]);
        });
    }
    return result;
}

void ReferenceSolver::clampToSampleRange(int field, const Eigen::ArrayXd& source,
                                         std::span<const glm::dvec3> departures,
                                         Eigen::ArrayXd& values) const {
    if (field == kPigmentField) {
        forEachPoint(cells_, [&](size_t point, glm::ivec3) {
            for (int channel = 0; channel < 4; ++channel) {
                const glm::dvec2 range = sampleCellRange(source, departures[point], 4, channel);
                double& v = values[Eigen::Index(point * 4 + size_t(channel))];
                v = std::clamp(v, range.x, range.y);
            }
        });
    } else {
        forEachPoint(faceCount(field), [&](size_t point, glm::ivec3 q) {
            double& v = values[Eigen::Index(point)];
            if (wallNormalFace(field, q)) {
                v = 0.0;
                return;
            }
            const glm::dvec2 range = sampleFaceRange(field, source, departures[point]);
            v = std::clamp(v, range.x, range.y);
        });
    }
}

} // namespace mfx::fluid
