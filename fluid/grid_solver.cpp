#include "fluid/grid_solver.h"

#include "fluid/smoke_solver.h"
#include "fluid/sparse_smoke_solver.h"

namespace mfx::fluid {

Result<std::unique_ptr<GridSolver>> createGridSolver(const gpu::Context& ctx,
                                                     const SolverOptions& options,
                                                     const DomainChoice& domain) {
    if (domain.sparse) {
        if (Status valid = validateSparseOptions(options); !valid) return valid.error();
        // Room for the first bricks; the atlas doubles up to the budget as the smoke spreads.
        auto sparse = SparseSmokeSolver::create(ctx, options, domain.maxBricks,
                                                std::min(domain.maxBricks, 64u));
        if (!sparse) return sparse.error();
        return std::unique_ptr<GridSolver>(std::move(sparse).value());
    }
    auto dense = SmokeSolver::create(ctx, options);
    if (!dense) return dense.error();
    return std::unique_ptr<GridSolver>(std::move(dense).value());
}

} // namespace mfx::fluid
