// vorticityConfinement (docs/fluid.md), after Fedkiw, Stam and Jensen 2001, eqs. 9-11:
// omega = curl u at cell centres (central differences of cell-centred velocity),
// N = grad|omega| / |grad|omega||, f = epsilon * h * (N x omega), added to each face as dt times
// the mean force of the two cells beside it. Off when epsilon is 0.
#include "fluid/reference/reference_solver.h"

#include <cmath>

namespace mfx::fluid {

void ReferenceSolver::vorticityConfinement() {
    if (options_.vorticity == 0.0f) return;
    const double epsilon = double(options_.vorticity);
    const Eigen::Index cellTotal = Eigen::Index(cells_.x) * cells_.y * cells_.z;

    // Cell-centred velocity component c of a possibly out-of-range cell.
    auto centred = [&](int c, glm::ivec3 q) {
        glm::ivec3 hi = q;
        hi[c] += 1;
        return 0.5 * (fetchFace(c, velocity_[c], q) + fetchFace(c, velocity_[c], hi));
    };
    const glm::ivec3 ex(1, 0, 0), ey(0, 1, 0), ez(0, 0, 1);
    const double inv2h = 1.0 / (2.0 * h_);

    // computeVorticity: (omega.xyz, |omega|) per cell.
    Eigen::ArrayXd vorticity(cellTotal * 4);
    for (int k = 0; k < cells_.z; ++k)
        for (int j = 0; j < cells_.y; ++j)
            for (int i = 0; i < cells_.x; ++i) {
                const glm::ivec3 q(i, j, k);
                const glm::dvec3 w{(centred(2, q + ey) - centred(2, q - ey) - centred(1, q + ez) +
                                    centred(1, q - ez)) *
                                       inv2h,
                                   (centred(0, q + ez) - centred(0, q - ez) - centred(2, q + ex) +
                                    centred(2, q - ex)) *
                                       inv2h,
                                   (centred(1, q + ex) - centred(1, q - ex) - centred(0, q + ey) +
                                    centred(0, q - ey)) *
                                       inv2h};
                const Eigen::Index base = Eigen::Index(cellIndex(q)) * 4;
                vorticity[base + 0] = w.x;
                vorticity[base + 1] = w.y;
                vorticity[base + 2] = w.z;
                vorticity[base + 3] = glm::length(w);
            }

    // Confinement force at a (clamped or wrapped) cell.
    auto force = [&](glm::ivec3 q) {
        const glm::dvec3 w{fetchCell(vorticity, q, 4, 0), fetchCell(vorticity, q, 4, 1),
                           fetchCell(vorticity, q, 4, 2)};
        const double magnitude = fetchCell(vorticity, q, 4, 3);
        const glm::dvec3 eta{
            (fetchCell(vorticity, q + ex, 4, 3) - fetchCell(vorticity, q - ex, 4, 3)) * inv2h,
            (fetchCell(vorticity, q + ey, 4, 3) - fetchCell(vorticity, q - ey, 4, 3)) * inv2h,
            (fetchCell(vorticity, q + ez, 4, 3) - fetchCell(vorticity, q - ez, 4, 3)) * inv2h};
        // Regularised normalisation: where |omega| barely varies there is nothing to confine.
        const glm::dvec3 normal = eta / (glm::length(eta) + 1e-3 * magnitude / h_ + 1e-20);
        return epsilon * h_ * glm::cross(normal, w);
    };

    // applyVorticityForce
    forEachFace([&](int c, glm::ivec3 q) {
        if (wallNormalFace(c, q) || solidFace(c, q)) return;
        glm::ivec3 below = q;
        below[c] -= 1;
        // Cells outside the grid are clamped or wrapped, as fetchCell does.
        const double f = 0.5 * (force(resolveCell(below))[c] + force(resolveCell(q))[c]);
        velocity_[c][Eigen::Index(faceIndex(c, q))] += dt() * f;
    });
}

} // namespace mfx::fluid
