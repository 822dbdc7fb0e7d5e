// Structures of the GPU pressure solvers beyond Jacobi (fluid/gpu_multigrid.h): red-black
// Gauss-Seidel, multigrid V-cycles and MGPCG, shared by their compute shaders and C++. The
// discretisation is docs/fluid.md, "Accuracy options"; the tables are made on the CPU from the
// reference's hierarchy (fluid/reference/pressure_equation.h).
//
// Every vector (pressure, right-hand side, residual, CG's vectors, on every level) lives in one
// storage buffer of vec4, four x-consecutive cells per element: element X + L * (y + ny * z),
// L = ceil(nx / 4), holds cells 4X .. 4X + 3 of row (y, z), and the cells past nx are padding that
// stays 0. A vector is named by the offset of its first element.
#ifndef MFX_SHARED_PRESSURE_SOLVE_H
#define MFX_SHARED_PRESSURE_SOLVE_H

#include "common.h"

// PressureDispatch.flags.
#define MFX_PRESSURE_PARTIAL_SUMS 1u  // write this workgroup's partial sums into slot `slot`
#define MFX_PRESSURE_ZERO_INPUT 2u    // relax_colour, cycle_coarse_levels: the x read is 0
#define MFX_PRESSURE_WARM_START 4u    // load_pressure_system: x from the pressure image, else 0
#define MFX_PRESSURE_SUBTRACT_MEAN 8u // remove_mean: subtract PressureScalars.mean
#define MFX_PRESSURE_SINGULAR 16u     // finish_reduction: no open face (A is singular)
#define MFX_PRESSURE_FIRST 32u        // finish_reduction / update_cg_direction: the first direction
#define MFX_PRESSURE_ZERO_IF_NO_RHS 64u // store_pressure: 0 when PressureScalars.zeroSolution
#define MFX_PRESSURE_COUNT_CELLS 128u   // finish_reduction (mean): the slot's y is the cell count

// Steps of finish_reduction (PressureDispatch.step).
#define MFX_REDUCE_MEAN 0u     // mean = sum / cells (the fluid cells, with solids)
#define MFX_REDUCE_CG_START 1u // ||b||, the first relative residual; stop at once if small enough
#define MFX_REDUCE_CG_ALPHA 2u // alpha = (r, z) / (d, A d); stop unless (d, A d) > 0
#define MFX_REDUCE_CG_CHECK 3u // one more iteration; the relative residual; stop if small enough
#define MFX_REDUCE_CG_BETA 4u  // z's mean, (r, z - mean), beta

MFX_SHARED_BEGIN

// One grid of the hierarchy (level 0: the simulation grid).
struct MultigridLevel {
    ivec4 cells;     // nx, ny, nz; w: vec4 elements per row, ceil(nx / 4)
    ivec4 axisCells; // first MultigridAxisCell of the x, y and z axis; w: nx * ny * nz
    // First MultigridRestriction of the x, y and z axis onto the next coarser level: R0 (the
    // multigrid solver's), and P^T (the MGPCG preconditioner's). w: the coarsest level's first
    // float of the coarsest solve's matrix.
    ivec4 restrictSum;
    ivec4 restrictTranspose;
    ivec4 vectors; // the level's x (two: relaxation ping-pongs between them), b and r
};

// One index along one axis of one level. The x axis has ceil(nx / 4) * 4 entries, those past nx
// all 0 and -1 (they count nothing).
struct MultigridAxisCell {
    // x: width in finest cells; y, z: 1 / distance to the low / high neighbour's centre (0 across
    // a wall). A side's coefficient is this times the product of the other two axes' widths.
    vec4 coefficients;
    // x, y: the low and high neighbour's index along the axis (-1: none: a wall, or an open face's
    // ghost with p = 0); z, w: the next coarser level's indices this one interpolates from (-1:
    // none).
    ivec4 neighbours;
    vec4 interpolation; // x, y: the weights of neighbours.z and neighbours.w; zw: 0
};

// Along one axis, the fine indices whose residuals go to one coarse index, with their weights.
struct MultigridRestriction {
    ivec4 fine; // -1: unused
    vec4 weight;
};

// Push constants of every pressure-solve kernel. Vectors are offsets in vec4 elements; each
// shader says which fields it reads.
struct PressureDispatch {
    int level;
    int source; // the vector read
    int result; // the vector written
    int rhs;
    int other;
    uint step;       // relax_colour: the colour (0 red, 1 black); finish_reduction: MFX_REDUCE_*
    uint slot;       // partial sums: the slot written, or the first of the two slots read
    uint flags;      // MFX_PRESSURE_*
    uint partials;   // partial sums per slot (the workgroups of a level-0 dispatch)
    float scale;     // load_pressure_system: -h^2; finish_reduction: the CG tolerance
    uint limit;      // finish_reduction: indirect dispatch entries to clear when CG stops;
                     // cycle_coarse_levels: the number of levels
    uint preSmooth;  // cycle_coarse_levels: red-black sweeps before the coarse correction ...
    uint postSmooth; // ... and after it
};

// The solver's scalars, on the GPU (storage buffer).
struct PressureScalars {
    float mean;              // what remove_mean subtracts; update_cg_direction: z's mean
    float rightHandSideNorm; // ||b|| (b mean-free when singular)
    float relativeResidual;  // CG's ||r|| / ||b||
    float alpha;
    float rz;          // (r, z) of the current direction
    float beta;        // of the current direction
    float dq;          // (d, A d)
    uint iterations;   // CG iterations run
    uint done;         // 1 once CG has stopped (its indirect dispatches are then all empty)
    uint zeroSolution; // b = 0: the solution is 0
    // The cells a mean is over: all of level 0's, or with solids its fluid ones (counted by
    // load_pressure_system, kept by finish_reduction's mean with MFX_PRESSURE_COUNT_CELLS).
    float fluidCells;
    uint pad1;
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(MultigridLevel, 80);
MFX_CHECK_LAYOUT(MultigridLevel, vectors, 64);
MFX_CHECK_LAYOUT(MultigridLevel, axisCells, 16);
MFX_CHECK_LAYOUT(MultigridLevel, restrictSum, 32);
MFX_CHECK_LAYOUT(MultigridLevel, restrictTranspose, 48);
MFX_CHECK_SIZE(MultigridAxisCell, 48);
MFX_CHECK_LAYOUT(MultigridAxisCell, neighbours, 16);
MFX_CHECK_LAYOUT(MultigridAxisCell, interpolation, 32);
MFX_CHECK_SIZE(MultigridRestriction, 32);
MFX_CHECK_LAYOUT(MultigridRestriction, weight, 16);
MFX_CHECK_SIZE(PressureDispatch, 52);
MFX_CHECK_LAYOUT(PressureDispatch, postSmooth, 48);
MFX_CHECK_LAYOUT(PressureDispatch, step, 20);
MFX_CHECK_LAYOUT(PressureDispatch, scale, 36);
MFX_CHECK_LAYOUT(PressureDispatch, limit, 40);
MFX_CHECK_SIZE(PressureScalars, 48);
MFX_CHECK_LAYOUT(PressureScalars, iterations, 28);
MFX_CHECK_LAYOUT(PressureScalars, done, 32);
MFX_CHECK_LAYOUT(PressureScalars, zeroSolution, 36);
MFX_CHECK_LAYOUT(PressureScalars, fluidCells, 40);
#endif

#endif
