// markSolids (docs/fluid.md, "Solids"): moving solids in the grid, after Bridson, "Fluid
// Simulation for Computer Graphics" (2nd ed., 2015), ch. 5 (solid wall boundary conditions:
// u·n = u_solid·n on the faces between fluid and solid, no pressure unknown inside the solid) and
// Crane, Llamas, Tariq, "Real-Time Simulation and Rendering of 3D Fluids" (GPU Gems 3, ch. 30:
// the obstacle voxelised into the grid every step, with the velocity of its surface). Each solid
// is a capsule (a sphere when its ends coincide) where the step ends, with the velocity of its two
// ends over the step. A cell is solid when its centre lies inside a capsule; a face is solid when
// a cell beside it is, and takes the solid's velocity at the face (the first capsule, in list
// order, holding the solid cell below the face, else the one above). Solid faces keep that
// velocity and solid cells hold no pigment through every stage (each stage's file says how). On
// the sparse domain only stored cells are solid: what is not stored is air at rest.
#include "fluid/reference/reference_solver.h"

#include <algorithm>
#include <stdexcept>

namespace mfx::fluid {

namespace {

// Where the closest point of the axis a-b to x lies along it, 0 at a and 1 at b.
double axisParameter(const shared::FluidSolid& s, glm::dvec3 x) {
    const glm::dvec3 a(s.endA), ab = glm::dvec3(s.endB) - a;
    const double length2 = glm::dot(ab, ab);
    return length2 > 0.0 ? std::clamp(glm::dot(x - a, ab) / length2, 0.0, 1.0) : 0.0;
}

bool inside(const shared::FluidSolid& s, glm::dvec3 x) {
    const double t = axisParameter(s, x);
    const glm::dvec3 closest = glm::mix(glm::dvec3(s.endA), glm::dvec3(s.endB), t);
    const glm::dvec3 d = x - closest;
    return glm::dot(d, d) < double(s.endA.w) * double(s.endA.w);
}

glm::dvec3 solidVelocityAt(const shared::FluidSolid& s, glm::dvec3 x) {
    return glm::mix(glm::dvec3(s.velocityA), glm::dvec3(s.velocityB), axisParameter(s, x));
}

} // namespace

void ReferenceSolver::setSolids(std::span<const shared::FluidSolid> solids) {
    if (Status ok = validateSolids(solids); !ok) throw std::invalid_argument(ok.error().message);
    if (Status ok = validateSolidOptions(options_); !solids.empty() && !ok)
        throw std::invalid_argument(ok.error().message);
    solids_.assign(solids.begin(), solids.end());
    markSolids();
}

void ReferenceSolver::markSolids() {
    if (solids_.empty()) {
        solidCells_.clear();
        return;
    }
    // The first solid holding each cell's centre (-1: none).
    std::vector<int> holder(size_t(cells_.x) * size_t(cells_.y) * size_t(cells_.z), -1);
    solidCells_.assign(holder.size(), 0);
    for (int k = 0; k < cells_.z; ++k)
        for (int j = 0; j < cells_.y; ++j)
            for (int i = 0; i < cells_.x; ++i) {
                const glm::ivec3 q(i, j, k);
                if (!cellActive(q)) continue; // not stored: air (sparse_solids.glsl)
                const glm::dvec3 x = cellCentre(q);
                for (size_t s = 0; s < solids_.size(); ++s)
                    if (inside(solids_[s], x)) {
                        holder[cellIndex(q)] = int(s);
                        solidCells_[cellIndex(q)] = 1;
                        break;
                    }
            }
    forEachFace([&](int c, glm::ivec3 q) {
        const Eigen::Index index = Eigen::Index(faceIndex(c, q));
        if (!solidFace(c, q)) return;
        glm::ivec3 below = q;
        below[c] -= 1;
        auto wrapped = [&](glm::ivec3 cell) {
            if (options_.periodic(c)) cell[c] = (cell[c] + cells_[c]) % cells_[c];
            return cell;
        };
        const bool belowSolid = below[c] >= 0 || options_.periodic(c)
                                    ? solidCells_[cellIndex(wrapped(below))] != 0
                                    : false;
        const glm::ivec3 cell = belowSolid ? wrapped(below) : wrapped(q);
        const shared::FluidSolid& s = solids_[size_t(holder[cellIndex(cell)])];
        velocity_[c][index] = solidVelocityAt(s, facePosition(c, q))[c];
    });
    for (size_t cell = 0; cell < solidCells_.size(); ++cell)
        if (solidCells_[cell] != 0)
            for (int channel = 0; channel < 4; ++channel)
                pigment_[Eigen::Index(cell * 4 + size_t(channel))] = 0.0;
    solidVelocity_ = velocity_; // what the solid faces hold from here on
}

bool ReferenceSolver::solidCell(glm::ivec3 q) const {
    return !solidCells_.empty() && solidCells_[cellIndex(q)] != 0;
}

bool ReferenceSolver::solidFace(int c, glm::ivec3 q) const {
    if (solidCells_.empty() || wallNormalFace(c, q)) return false; // a wall stays a wall
    glm::ivec3 below = q;
    below[c] -= 1;
    for (glm::ivec3 cell : {below, q}) {
        if (options_.periodic(c))
            cell[c] = (cell[c] + cells_[c]) % cells_[c];
        else if (cell[c] < 0 || cell[c] >= cells_[c])
            continue;
        if (solidCells_[cellIndex(cell)] != 0) return true;
    }
    return false;
}

void ReferenceSolver::keepSolidFaces(std::array<Eigen::ArrayXd, 3>& velocity) const {
    if (solidCells_.empty()) return;
    forEachFace([&](int c, glm::ivec3 q) {
        if (solidFace(c, q)) {
            const Eigen::Index index = Eigen::Index(faceIndex(c, q));
            velocity[c][index] = solidVelocity_[c][index];
        }
    });
}

double ReferenceSolver::sampleCellOutsideSolids(const Eigen::ArrayXd& field, glm::dvec3 x,
                                                int channels, int channel) const {
    if (solidCells_.empty()) return sampleCell(field, x, channels, channel);
    const glm::dvec3 g = x / h_ - 0.5;
    const glm::dvec3 base = glm::floor(g);
    const glm::dvec3 f = g - base;
    const glm::ivec3 i0(base);
    double sum = 0.0, weight = 0.0;
    bool anySolid = false;
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                const glm::ivec3 cell = resolveCell(i0 + glm::ivec3(dx, dy, dz));
                if (solidCells_[cellIndex(cell)] != 0) {
                    anySolid = true;
                    continue;
                }
                const double w =
                    (dx ? f.x : 1.0 - f.x) * (dy ? f.y : 1.0 - f.y) * (dz ? f.z : 1.0 - f.z);
                sum +=
                    w * field[Eigen::Index(cellIndex(cell) * size_t(channels) + size_t(channel))];
                weight += w;
            }
    // Away from the solids the plain sample, to the bit.
    if (!anySolid) return sampleCell(field, x, channels, channel);
    return weight > 0.0 ? sum / weight : 0.0;
}

} // namespace mfx::fluid
