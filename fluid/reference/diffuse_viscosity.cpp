// diffuseViscosity (docs/fluid.md): implicit diffusion (I - nu dt Laplacian) u_new = u, solved per
// component with a fixed number of Jacobi sweeps, x <- (u + alpha * sum of 6 neighbours) / (1 + 6
// alpha), alpha = nu dt / h². Unconditionally stable (Stam 1999, sec. 3). Off when nu is 0. With
// fp16 storage every sweep's result is rounded, as the GPU stores each in a velocity image.
#include "fluid/reference/reference_solver.h"

namespace mfx::fluid {

void ReferenceSolver::diffuseViscosity() {
    if (options_.viscosity == 0.0f || options_.viscosityIterations == 0) return;
    const double alpha = double(options_.viscosity) * dt() / (h_ * h_);
    const glm::ivec3 steps[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                 {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    for (int c = 0; c < 3; ++c) {
        const Eigen::ArrayXd source = velocity_[c];
        Eigen::ArrayXd x = source;
        Eigen::ArrayXd next = source;
        const glm::ivec3 n = faceCount(c);
        for (uint32_t iteration = 0; iteration < options_.viscosityIterations; ++iteration) {
            for (int k = 0; k < n.z; ++k)
                for (int j = 0; j < n.y; ++j)
                    for (int i = 0; i < n.x; ++i) {
                        const glm::ivec3 q(i, j, k);
                        const Eigen::Index index = Eigen::Index(faceIndex(c, q));
                        if (wallNormalFace(c, q)) {
                            next[index] = 0.0;
                            continue;
                        }
                        if (solidFace(c, q)) { // the solid's velocity, a fixed boundary value
                            next[index] = source[index];
                            continue;
                        }
                        double sum = 0.0;
                        for (const glm::ivec3& s : steps)
                            sum += fetchFace(c, x, q + s);
                        next[index] = (source[index] + alpha * sum) / (1.0 + 6.0 * alpha);
                    }
            if (options_.storage == Storage::Float16) // each sweep lands in a 16-bit image
                roundToHalf(next);
            std::swap(x, next);
        }
        velocity_[c] = x;
    }
}

} // namespace mfx::fluid
