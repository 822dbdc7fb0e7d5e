// The operations of a multigrid V-cycle on one brick of a level (shaders/fluid/pressure_solve_common.glsl,
// levelBrick), as functions of the level and the vectors they read and write: shared by the
// kernel that runs each one over a whole level (relax_colour, compute_residual,
// apply_pressure_operator, restrict_residual, prolong_correction) and by cycle_coarse_levels,
// which runs the coarse levels' whole V-cycle in one workgroup. Twins: PressureGrid::relaxColour
// and PressureGrid::residual (fluid/reference/red_black_gauss_seidel.cpp,
// pressure_equation.cpp), Multigrid::restrictSum, restrictTranspose, prolong and solveCoarsest
// (fluid/reference/multigrid.cpp); Trottenberg, Oosterlee, Schueller, "Multigrid" (2001), ch. 2;
// McAdams, Sifakis, Teran (SCA 2010).
#ifndef MFX_PRESSURE_MULTIGRID_GLSL
#define MFX_PRESSURE_MULTIGRID_GLSL

#include "pressure_solve_common.glsl"

// Coarse indices a prolongation brick reads along each axis (from the brick's first fine index's
// parent - 1 on), and fine indices a P^T restriction brick reads along x (for its four coarse
// cells) and along y or z (for its rows or layers, from its first coarse index's first fine index
// on). GpuMultigrid sizes them from the tables: 4 and 10 for bricks of 4.
layout(constant_id = 5) const int kProlongSlots = 4;
layout(constant_id = 6) const int kRestrictSlotsX = 10;
layout(constant_id = 7) const int kRestrictSlotsYZ = 10;
// Which V-cycle the solver runs: the multigrid solver's (restriction R0) or the MGPCG
// preconditioner's (P^T, and black-red post-smoothing): only one is compiled.
layout(constant_id = 8) const bool kSymmetric = false;
// The multigrid solver's restriction computes the residual it restricts (no residual pass before
// it): MultigridOptions::residualInRestriction.
layout(constant_id = 9) const bool kResidualInRestriction = false;
// Whether the V-cycle runs a residual pass before its restriction.
const bool kResidualPass = kSymmetric || !kResidualInRestriction;

// --- Stencils: red-black relaxation, residual, A p ------------------------------------------------

// What visitRow does with the rows stencilBrick visits, set by the functions below.
const int kVisitRelax = 0;
const int kVisitResidual = 1;
const int kVisitApply = 2;
const int kVisitRestrict = 3;
int visitMode = kVisitRelax;
int visitLevel = 0;
int visitRhs = 0;
int visitResult = 0;
int visitColour = 0;
// Sums over the rows visited: residual: sum r; A p: (p, A p).
vec4 visitSums = vec4(0.0);
// kVisitRestrict: the coarse brick (its first element, row and layer) whose right-hand side the
// visited rows' residuals are summed into, by the coarse cell each fine cell lies in; the P^T
// restriction sums into visitCoarse too (storeCoarseBrick writes it).
ivec3 visitCoarseOrigin = ivec3(0);
vec4 visitCoarse[kBrickLayers][kBrickRows];

void visitRow(ivec3 q, int element, vec4 centre, vec4 weighted, vec4 total) {
    if (visitMode == kVisitRelax) {
        // Red-black Gauss-Seidel: the colour's cells relaxed, the other colour's copied,
        //   p_q <- (sum_s c_s p_n(s) + b_q) / sum_s c_s   (0 where nothing is counted).
        vec4 b = vectors[visitRhs + element];
        vec4 relaxed = mix((weighted + b) / total, vec4(0.0), equal(total, vec4(0.0)));
        // (Past the last cell the tables count nothing: total = 0 and the padding stays 0.)
        bvec4 colour = equal((elementColumns(q.x) + q.y + q.z) & 1, ivec4(visitColour));
        vectors[visitResult + element] = mix(centre, relaxed, colour);
    } else if (visitMode == kVisitResidual) {
        vec4 r = vectors[visitRhs + element] - (total * centre - weighted); // padding: 0
        vectors[visitResult + element] = r;
        visitSums.x += r.x + r.y + r.z + r.w;
    } else if (visitMode == kVisitRestrict) {
        // R0 of the residual: each fine cell's r into its parent (MultigridAxisCell's
        // neighbours.z) when the parent lies in the coarse brick (padding: parent -1).
        vec4 r = vectors[visitRhs + element] - (total * centre - weighted);
        ivec4 axes = levels[visitLevel].axisCells;
        int row = axisCells[axes.y + q.y].neighbours.z - visitCoarseOrigin.y;
        int layer = axisCells[axes.z + q.z].neighbours.z - visitCoarseOrigin.z;
        if (row < 0 || row >= kBrickRows || layer < 0 || layer >= kBrickLayers) return;
        for (int c = 0; c < 4; ++c) {
            int column = axisCells[axes.x + 4 * q.x + c].neighbours.z - 4 * visitCoarseOrigin.x;
            if (column >= 0 && column < 4) visitCoarse[layer][row][column] += r[c];
        }
    } else {
        vec4 product = total * centre - weighted;
        vectors[visitResult + element] = product;
        visitSums.x += dot(centre, product);
    }
}

// One half-sweep of red-black Gauss-Seidel on the brick: the cells of `colour` (0 red:
// i + j + k even, 1 black) relaxed from `source` (0 everywhere with `zero`) into `result`, the
// others copied. Source and result differ, so a wrap onto a cell of the same colour (an odd
// periodic axis) reads the old value, as the reference does.
void relaxBrick(int level, int source, int result, int rhs, int colour, bool zero,
                ivec3 origin) {
    visitMode = kVisitRelax;
    visitLevel = level;
    visitRhs = rhs;
    visitResult = result;
    visitColour = colour;
    stencilBrick(level, source, origin, zero);
}

// r = b - A p.
void residualBrick(int level, int source, int result, int rhs, ivec3 origin) {
    visitMode = kVisitResidual;
    visitLevel = level;
    visitRhs = rhs;
    visitResult = result;
    stencilBrick(level, source, origin, false);
}

// q = A d (level 0).
void applyBrick(int source, int result, ivec3 origin) {
    visitMode = kVisitApply;
    visitLevel = 0;
    visitResult = result;
    stencilBrick(0, source, origin, false);
}

// --- Transfers ------------------------------------------------------------------------------------
//
// Restriction: level `level`'s residual (`source`) onto a brick of level `level` + 1: its b
// (`result`), and its correction (`correction`) set to 0, the start of the coarse solve.

// Fine index `u` along an axis of the fine level, unwrapped (u < 0 or u >= n only across a
// periodic face), wrapped.
int fineIndex(int n, int u) {
    return u < 0 ? u + n : (u >= n ? u - n : u);
}

// A restriction's result: the coarse brick at `origin` (its rows and layers inside the level, of
// `cells`) takes visitCoarse as its b (`result`) and 0 as its correction.
void storeCoarseBrick(ivec4 cells, ivec3 origin, int result, int correction) {
    for (int l = 0; l < kBrickLayers; ++l)
        for (int r = 0; r < kBrickRows; ++r) {
            ivec3 q = origin + ivec3(0, r, l);
            if (q.y >= cells.y || q.z >= cells.z) continue;
            int element = elementIndex(cells, q.x, q.y, q.z);
            vectors[result + element] = visitCoarse[l][r];
            vectors[correction + element] = vec4(0.0);
        }
}

// R0: each coarse cell sums the residuals of the (up to 2 x 2 x 2) fine cells it covers.
void restrictSumBrick(int level, int source, int result, int correction, ivec3 origin) {
    int coarse = level + 1;
    ivec4 cells = levels[coarse].cells;
    ivec4 fineCells = levels[level].cells;
    ivec4 lists = levels[level].restrictSum;
    bvec4 inside = insideColumns(cells, origin.x);
    ivec2 fineX[4];
    for (int c = 0; c < 4; ++c)
        fineX[c] = inside[c] ? restrictions[lists.x + 4 * origin.x + c].fine.xy : ivec2(-1);
    for (int layer = 0; layer < kBrickLayers; ++layer) {
        int z = origin.z + layer;
        if (z >= cells.z) break;
        ivec2 fineZ = restrictions[lists.z + z].fine.xy;
        for (int row = 0; row < kBrickRows; ++row) {
            int y = origin.y + row;
            if (y >= cells.y) break;
            ivec2 fineY = restrictions[lists.y + y].fine.xy;
            vec4 b = vec4(0.0);
            for (int kz = 0; kz < 2; ++kz) {
                if (fineZ[kz] < 0) continue;
                for (int ky = 0; ky < 2; ++ky) {
                    if (fineY[ky] < 0) continue;
                    int rowStart =
                        4 * (source + elementIndex(fineCells, 0, fineY[ky], fineZ[kz]));
                    for (int c = 0; c < 4; ++c)
                        for (int kx = 0; kx < 2; ++kx)
                            if (fineX[c][kx] >= 0) b[c] += vectorCells[rowStart + fineX[c][kx]];
                }
            }
            int element = elementIndex(cells, origin.x, y, z);
            vectors[result + element] = b;
            vectors[correction + element] = vec4(0.0);
        }
    }
}

// The same with the residual r = b - A p computed here from p (`source`) and b (`rhs`), by the
// stencil compute_residual runs (the same arithmetic, so the same r), rather than read from a
// vector a dispatch wrote before: one dispatch and a write and a read of r fewer per level
// (kResidualInRestriction). The
// fine cells of the brick's coarse cells are visited as fine bricks from the first one's first
// fine cell: 2 x 2 x 2 of them where each axis halves from an even start; a parent shifted by
// a lone first cell (Multigrid's constructor) visits three fine elements along x instead of two.
void restrictResidualSumBrick(int level, int source, int rhs, int result, int correction,
                               ivec3 origin) {
    int coarse = level + 1;
    ivec4 cells = levels[coarse].cells;
    ivec4 lists = levels[level].restrictSum;
    ivec3 last = ivec3(min(4 * origin.x + 3, cells.x - 1), min(origin.y + kBrickRows - 1, cells.y - 1),
                       min(origin.z + kBrickLayers - 1, cells.z - 1));
    // The fine range: the first coarse cell's first fine cell to the last one's last.
    ivec3 first = ivec3(restrictions[lists.x + 4 * origin.x].fine.x,
                        restrictions[lists.y + origin.y].fine.x,
                        restrictions[lists.z + origin.z].fine.x);
    ivec2 lastX = restrictions[lists.x + last.x].fine.xy;
    ivec2 lastY = restrictions[lists.y + last.y].fine.xy;
    ivec2 lastZ = restrictions[lists.z + last.z].fine.xy;
    ivec3 end = ivec3(max(lastX.x, lastX.y), max(lastY.x, lastY.y), max(lastZ.x, lastZ.y));

    for (int l = 0; l < kBrickLayers; ++l)
        for (int r = 0; r < kBrickRows; ++r)
            visitCoarse[l][r] = vec4(0.0);
    visitMode = kVisitRestrict;
    visitLevel = level;
    visitRhs = rhs;
    visitCoarseOrigin = origin;
    for (int z = first.z; z <= end.z; z += kBrickLayers)
        for (int y = first.y; y <= end.y; y += kBrickRows)
            for (int x = first.x / 4; x <= end.x / 4; ++x)
                stencilBrick(level, source, ivec3(x, y, z), false);
    storeCoarseBrick(cells, origin, result, correction);
}

// P^T: separably, each fine row restricted along x once (to the brick's four coarse cells), then
// along y and z into every coarse row of the brick. The loop over fine layers is left rolled (its
// bound is the brick's own count), which keeps the unrolled body, and its compile time, small.
void restrictTransposeBrick(int level, int source, int result, int correction, ivec3 origin) {
    int coarse = level + 1;
    ivec4 cells = levels[coarse].cells;
    ivec4 fineCells = levels[level].cells;
    ivec4 lists = levels[level].restrictTranspose;
    bvec4 inside = insideColumns(cells, origin.x);
    int baseX = restrictions[lists.x + 4 * origin.x].fine.x;
    int baseY = restrictions[lists.y + origin.y].fine.x;
    int baseZ = restrictions[lists.z + origin.z].fine.x;
    vec4 weightX[kRestrictSlotsX];
    float weightY[kRestrictSlotsYZ][kBrickRows];
    for (int s = 0; s < kRestrictSlotsX; ++s)
        weightX[s] = vec4(0.0);
    for (int s = 0; s < kRestrictSlotsYZ; ++s)
        for (int r = 0; r < kBrickRows; ++r)
            weightY[s][r] = 0.0;
    for (int c = 0; c < 4; ++c) {
        if (!inside[c]) continue;
        ivec4 fine = restrictions[lists.x + 4 * origin.x + c].fine - baseX;
        vec4 weight = restrictions[lists.x + 4 * origin.x + c].weight;
        for (int k = 0; k < 4; ++k)
            for (int s = 0; s < kRestrictSlotsX; ++s)
                weightX[s][c] += fine[k] == s ? weight[k] : 0.0;
    }
    for (int r = 0; r < kBrickRows; ++r) {
        if (origin.y + r >= cells.y) break;
        ivec4 fine = restrictions[lists.y + origin.y + r].fine - baseY;
        vec4 weight = restrictions[lists.y + origin.y + r].weight;
        for (int k = 0; k < 4; ++k)
            for (int s = 0; s < kRestrictSlotsYZ; ++s)
                weightY[s][r] += fine[k] == s ? weight[k] : 0.0;
    }
    // z: each layer's list, and the brick's fine layers (up to its last layer's last index).
    ivec4 fineZ[kBrickLayers];
    vec4 weightZ[kBrickLayers];
    int lastZ = baseZ;
    for (int l = 0; l < kBrickLayers; ++l) {
        int z = min(origin.z + l, cells.z - 1);
        fineZ[l] = restrictions[lists.z + z].fine - baseZ;
        weightZ[l] = origin.z + l < cells.z ? restrictions[lists.z + z].weight : vec4(0.0);
        lastZ = max(lastZ, baseZ + max(max(fineZ[l].x, fineZ[l].y), max(fineZ[l].z, fineZ[l].w)));
    }
    int columnX[kRestrictSlotsX];
    for (int s = 0; s < kRestrictSlotsX; ++s)
        columnX[s] = fineIndex(fineCells.x, baseX + s);

    for (int l = 0; l < kBrickLayers; ++l)
        for (int r = 0; r < kBrickRows; ++r)
            visitCoarse[l][r] = vec4(0.0);
    for (int sz = 0; sz <= lastZ - baseZ; ++sz) {
        int z = fineIndex(fineCells.z, baseZ + sz);
        vec4 alongY[kBrickRows];
        for (int r = 0; r < kBrickRows; ++r)
            alongY[r] = vec4(0.0);
        for (int sy = 0; sy < kRestrictSlotsYZ; ++sy) {
            int y = fineIndex(fineCells.y, baseY + sy);
            if (y < 0 || y >= fineCells.y) continue; // past the brick's last fine row
            int rowStart = 4 * (source + elementIndex(fineCells, 0, y, z));
            vec4 alongX = vec4(0.0);
            for (int s = 0; s < kRestrictSlotsX; ++s)
                if (columnX[s] >= 0 && columnX[s] < fineCells.x)
                    alongX += weightX[s] * vectorCells[rowStart + columnX[s]];
            for (int r = 0; r < kBrickRows; ++r)
                alongY[r] += weightY[sy][r] * alongX;
        }
        for (int l = 0; l < kBrickLayers; ++l) {
            float w = 0.0;
            for (int k = 0; k < 4; ++k)
                w += fineZ[l][k] == sz ? weightZ[l][k] : 0.0;
            for (int r = 0; r < kBrickRows; ++r)
                visitCoarse[l][r] += w * alongY[r];
        }
    }
    storeCoarseBrick(cells, origin, result, correction);
}

// Coarse index `u` along an axis of the coarse level, given relative to the axis (-1 and n lie
// beyond its faces: wrapped on a periodic axis, else none, -1).
int coarseIndex(int axisStart, int n, int u) {
    if (u >= 0 && u < n) return u;
    if (u == -1) return axisCells[axisStart].neighbours.x;
    if (u == n) return axisCells[axisStart + n - 1].neighbours.y;
    return -1;
}

// The weights of slot s (coarse index base + s) for a fine index interpolating from its parent's
// slot `parent` and the slot beside it on side `side`.
float slotWeight(int s, int parent, int side, vec2 weights) {
    return (s == parent ? weights.x : 0.0) + (s == parent + side ? weights.y : 0.0);
}

// Prolongation: level `level`'s p (`result`) += P e, e level `level` + 1's correction
// (`source`): trilinear interpolation at each fine cell centre, along each axis between the two
// nearest coarse centres (beyond the last one: a wall repeats it, an open face interpolates
// towards 0 at its ghost, a periodic axis wraps; the weights are the reference's); nothing added
// to a solid cell. Separably: each coarse row interpolated along x once, then along y and z into
// every fine row of the brick.
void prolongBrick(int level, int source, int result, ivec3 origin) {
    ivec4 cells = levels[level].cells;
    ivec4 axes = levels[level].axisCells;
    ivec4 coarseCells = levels[level + 1].cells;
    ivec4 coarseAxes = levels[level + 1].axisCells;

    // Per axis, the brick's coarse indices (slots) and each fine index's weight on each slot.
    int baseX = axisCells[axes.x + 4 * origin.x].neighbours.z - 1;
    int baseY = axisCells[axes.y + origin.y].neighbours.z - 1;
    int baseZ = axisCells[axes.z + origin.z].neighbours.z - 1;
    int columnX[kProlongSlots], rowY[kProlongSlots], layerZ[kProlongSlots];
    vec4 weightX[kProlongSlots];
    float weightY[kProlongSlots][kBrickRows], weightZ[kProlongSlots][kBrickLayers];
    for (int s = 0; s < kProlongSlots; ++s) {
        columnX[s] = coarseIndex(coarseAxes.x, coarseCells.x, baseX + s);
        rowY[s] = coarseIndex(coarseAxes.y, coarseCells.y, baseY + s);
        layerZ[s] = coarseIndex(coarseAxes.z, coarseCells.z, baseZ + s);
        weightX[s] = vec4(0.0);
        for (int r = 0; r < kBrickRows; ++r)
            weightY[s][r] = 0.0;
        for (int l = 0; l < kBrickLayers; ++l)
            weightZ[s][l] = 0.0;
    }
    for (int c = 0; c < 4; ++c) {
        int i = 4 * origin.x + c; // past the last cell the table holds parent -1, weights 0
        int parent = axisCells[axes.x + i].neighbours.z - baseX;
        vec4 interp = axisCells[axes.x + i].interpolation;
        for (int s = 0; s < kProlongSlots; ++s)
            weightX[s][c] = slotWeight(s, parent, int(interp.z), interp.xy);
    }
    for (int r = 0; r < kBrickRows; ++r) {
        int y = min(origin.y + r, cells.y - 1);
        int parent = axisCells[axes.y + y].neighbours.z - baseY;
        vec4 interp = axisCells[axes.y + y].interpolation;
        for (int s = 0; s < kProlongSlots; ++s)
            weightY[s][r] = slotWeight(s, parent, int(interp.z), interp.xy);
    }
    for (int l = 0; l < kBrickLayers; ++l) {
        int z = min(origin.z + l, cells.z - 1);
        int parent = axisCells[axes.z + z].neighbours.z - baseZ;
        vec4 interp = axisCells[axes.z + z].interpolation;
        for (int s = 0; s < kProlongSlots; ++s)
            weightZ[s][l] = slotWeight(s, parent, int(interp.z), interp.xy);
    }

    // Separably: each coarse row interpolated along x once, then along y and z into every fine
    // row of the brick.
    vec4 correction[kBrickLayers][kBrickRows];
    for (int l = 0; l < kBrickLayers; ++l)
        for (int r = 0; r < kBrickRows; ++r)
            correction[l][r] = vec4(0.0);
    for (int sz = 0; sz < kProlongSlots; ++sz) {
        if (layerZ[sz] < 0) continue;
        vec4 alongY[kBrickRows];
        for (int r = 0; r < kBrickRows; ++r)
            alongY[r] = vec4(0.0);
        for (int sy = 0; sy < kProlongSlots; ++sy) {
            if (rowY[sy] < 0) continue;
            int rowStart = 4 * (source + elementIndex(coarseCells, 0, rowY[sy], layerZ[sz]));
            vec4 alongX = vec4(0.0);
            for (int s = 0; s < kProlongSlots; ++s)
                if (columnX[s] >= 0) alongX += weightX[s] * vectorCells[rowStart + columnX[s]];
            for (int r = 0; r < kBrickRows; ++r)
                alongY[r] += weightY[sy][r] * alongX;
        }
        for (int l = 0; l < kBrickLayers; ++l)
            for (int r = 0; r < kBrickRows; ++r)
                correction[l][r] += weightZ[sz][l] * alongY[r];
    }
    for (int l = 0; l < kBrickLayers; ++l)
        for (int r = 0; r < kBrickRows; ++r) {
            ivec3 q = origin + ivec3(0, r, l);
            if (q.y >= cells.y || q.z >= cells.z) continue;
            int element = elementIndex(cells, q.x, q.y, q.z);
            // No unknown in a solid cell (level 0 with solids): it stays 0.
            vec4 add = mix(correction[l][r], vec4(0.0), solidCells(level, element));
            vectors[result + element] += add;
        }
}

// The solver's restriction onto the coarse brick at `origin`. kSymmetric: P^T of the residual
// vector `source`; else R0, of the residual vector `source` or, with kResidualInRestriction, of
// the residual of p = `source` for b = `rhs`, computed here.
void restrictBrick(int level, int source, int rhs, int result, int correction, ivec3 origin) {
    if (kSymmetric)
        restrictTransposeBrick(level, source, result, correction, origin);
    else if (kResidualInRestriction)
        restrictResidualSumBrick(level, source, rhs, result, correction, origin);
    else
        restrictSumBrick(level, source, result, correction, origin);
}

// --- The coarsest level ---------------------------------------------------------------------------

// The packed float index of cell `index` (x-fastest) of vector `base` on a level.
int cellFloat(int base, ivec4 cells, int index) {
    int x = index % cells.x;
    int row = index / cells.x;
    return 4 * (base + cells.w * row) + x;
}

// Cell i of the coarsest level's e = M b, M its exact solution operator, computed once on the CPU
// by the reference (Multigrid::solveCoarsest applied to each unit vector: a sparse LDL^T solve;
// without an open face b made mean-free, one cell pinned and the solution made mean-free: the
// pseudo-inverse) and stored dense.
void solveCoarsestCell(int level, int source, int result, int i) {
    ivec4 cells = levels[level].cells;
    int n = levels[level].axisCells.w;
    int matrix = levels[level].restrictTranspose.w + i * n;
    // Four terms per iteration: a CPU driver (llvmpipe) ends an invocation's loops after 65535
    // iterations in all (GpuMultigrid::kMaxCoarsestCells).
    float e = 0.0;
    for (int j = 0; j < n; j += 4)
        for (int k = 0; k < 4; ++k)
            if (j + k < n)
                e += coarsestMatrix[matrix + j + k] * vectorCells[cellFloat(source, cells, j + k)];
    vectorCells[cellFloat(result, cells, i)] = e;
}

#endif
