// Shared by the kernels of the GPU pressure solvers beyond Jacobi (fluid/gpu_multigrid.h): the
// resources, the packed vectors (shaders/shared/pressure_solve.h) and the finite-volume stencil
// of a level, as fluid/reference/pressure_equation.cpp computes it:
//   (A p)_q = sum over the sides s of q of c_s (p_q - p_n(s)),
//   c_s = (1 / distance between the centres) * (area of the side),
// the sides in the order -x, +x, -y, +y, -z, +z, a neighbour across a periodic face wrapped, an
// open face's ghost counted with p = 0, a wall not counted (c_s = 0). On the simulation grid every
// counted c_s is 1: the Jacobi sweep's system (docs/fluid.md, step 10).
//
// Every kernel but cycle_coarse_levels and finish_reduction runs one invocation per brick of a
// level (see levelBrick).
#ifndef MFX_PRESSURE_SOLVE_COMMON_GLSL
#define MFX_PRESSURE_SOLVE_COMMON_GLSL

#include "field_formats.glsl"
#include "shared/pressure_solve.h"

// The workgroup shape (SolverOptions::workgroup), by specialization.
layout(local_size_x_id = 0, local_size_y_id = 1, local_size_z_id = 2) in;

layout(std430, binding = 0) readonly buffer Levels {
    MultigridLevel levels[];
};
layout(std430, binding = 1) readonly buffer AxisCells {
    MultigridAxisCell axisCells[];
};
layout(std430, binding = 2) readonly buffer Restrictions {
    MultigridRestriction restrictions[];
};
layout(std430, binding = 3) readonly buffer CoarsestMatrix {
    float coarsestMatrix[];
};
// Coherent where one invocation reads what another wrote in the same dispatch
// (cycle_coarse_levels).
#ifndef MFX_PRESSURE_COHERENT
#define MFX_PRESSURE_COHERENT
#endif
layout(std430, binding = 4) MFX_PRESSURE_COHERENT buffer Vectors {
    vec4 vectors[];
};
// The same buffer as Vectors, cell by cell.
layout(std430, binding = 5) MFX_PRESSURE_COHERENT buffer VectorCells {
    float vectorCells[];
};
layout(std430, binding = 6) buffer Partials {
    vec4 partials[];
};
layout(std430, binding = 7) buffer Scalars {
    PressureScalars scalars;
};
layout(std430, binding = 8) buffer Arguments {
    uvec4 arguments[];
};
layout(binding = 9, r32f) uniform readonly image3D divergence;
layout(binding = 10, MFX_PRESSURE_FORMAT) uniform readonly image3D pressure;
layout(std430, binding = 11) writeonly buffer PressureOut {
    float pressureOut[];
};

// Solids (constant id 15; docs/fluid.md, "Solids"): the solid flag bytes of level 0, one per
// cell in its vectors' layout (element X + L (y + ny z) is the word of cells 4X .. 4X + 3 of row
// (y, z); bit 0 the cell is solid, bit 1 + s its neighbour on side s is; written by
// mark_solids.comp, fluid_solids.glsl). On level 0 a solid cell has no unknown (its row of A is 0,
// its value stays 0) and a side towards a solid cell is not counted; the coarse levels do not see
// them (fluid/reference/pressure_equation.h).
layout(constant_id = 15) const bool kSolids = false;
layout(std430, binding = 15) readonly buffer SolidFlags {
    uint solidFlags[];
};

// The four flag bytes of level `level`'s element `element` (0 without solids, or off level 0).
uvec4 solidBytes(int level, int element) {
    if (!kSolids || level != 0) return uvec4(0u);
    return (uvec4(solidFlags[element]) >> uvec4(0u, 8u, 16u, 24u)) & 0xffu;
}

// Which of the element's four cells are solid.
bvec4 solidCells(int level, int element) {
    return notEqual(solidBytes(level, element) & 1u, uvec4(0u));
}

layout(push_constant) uniform Dispatch {
    PressureDispatch pc;
};

bool hasFlag(uint flag) {
    return (pc.flags & flag) != 0u;
}

// The brick of rows each invocation handles: one element (four cells along x) by kBrickRows rows
// (y) by kBrickLayers layers (z), so that a row loaded serves several cells and the tables of a
// brick are loaded once (on a CPU driver every loaded channel of every lane costs about the same).
layout(constant_id = 3) const int kBrickRows = 4;
layout(constant_id = 4) const int kBrickLayers = 4;

// This invocation's brick on level `level`: its first element (x in elements, y, z); false past
// the level.
bool levelBrick(int level, out ivec3 origin) {
    origin = ivec3(gl_GlobalInvocationID) * ivec3(1, kBrickRows, kBrickLayers);
    ivec4 cells = levels[level].cells;
    return origin.x < cells.w && origin.y < cells.y && origin.z < cells.z;
}

int elementIndex(ivec4 cells, int x, int y, int z) {
    return x + cells.w * (y + cells.y * z);
}

// The x indices of an element's four cells, and which of them lie inside the level.
ivec4 elementColumns(int x) {
    return 4 * x + ivec4(0, 1, 2, 3);
}
bvec4 insideColumns(ivec4 cells, int x) {
    return lessThan(elementColumns(x), ivec4(cells.x));
}

// A row of vector `base` at (y, z), or 0 for a missing neighbour (index -1). The load is made
// either way (from row 0) and the value selected after: branch-free, which a CPU driver runs
// faster than a load under a condition.
vec4 rowAt(int base, ivec4 cells, int x, int y, int z) {
    vec4 row = vectors[base + elementIndex(cells, x, max(y, 0), max(z, 0))];
    return y >= 0 && z >= 0 ? row : vec4(0.0);
}

// Called by stencilBrick for every row of the brick inside the level: the element (x, y, z), its
// index, its four values of p, and the sums over their sides, weighted = sum c_s p_n(s) and
// total = sum c_s, in the order -x, +x, -y, +y, -z, +z. Each stencil kernel defines it.
void visitRow(ivec3 q, int element, vec4 centre, vec4 weighted, vec4 total);

// Visits the brick at `origin` of vector `base` on level `level`. With `zero`, p is 0 everywhere
// and nothing is read. Rows slide along z (the layer above becomes the centre, the centre the
// layer below) and each layer's rows are read once with a row either side for the y neighbours.
void stencilBrick(int level, int base, ivec3 origin, bool zero) {
    ivec4 cells = levels[level].cells;
    ivec4 axes = levels[level].axisCells;
    int x = origin.x;
    int first = 4 * x;
    vec4 x0 = axisCells[axes.x + first].coefficients;
    vec4 x1 = axisCells[axes.x + first + 1].coefficients;
    vec4 x2 = axisCells[axes.x + first + 2].coefficients;
    vec4 x3 = axisCells[axes.x + first + 3].coefficients;
    vec4 width = vec4(x0.x, x1.x, x2.x, x3.x);
    vec4 inverseLowX = vec4(x0.y, x1.y, x2.y, x3.y);
    vec4 inverseHighX = vec4(x0.z, x1.z, x2.z, x3.z);
    // x: the row shifted by one, the ends from the cells beyond the element (wrapped on a periodic
    // axis; none, 0, on a wall or an open face). A cell's -x neighbour inside the element is
    // always inside the level; its +x neighbour may be past the last cell, and then is the last
    // cell's high neighbour.
    int leftIndex = first > 0 ? first - 1 : axisCells[axes.x].neighbours.x;
    int rightIndex =
        first + 4 < cells.x ? first + 4 : axisCells[axes.x + cells.x - 1].neighbours.y;
    bvec4 plusPast = greaterThanEqual(first + ivec4(1, 2, 3, 4), ivec4(cells.x));

    // y: the window of rows origin.y - 1 .. origin.y + kBrickRows, out-of-range ones replaced by
    // the first row's low neighbour or the last row's high one (wrapped, or -1: none). Brick row
    // r is window row r + 1; its -y and +y neighbours are window rows r and r + 2.
    int lowY = axisCells[axes.y].neighbours.x;
    int highY = axisCells[axes.y + cells.y - 1].neighbours.y;
    int windowY[kBrickRows + 2];
    for (int i = 0; i < kBrickRows + 2; ++i) {
        int y = origin.y - 1 + i;
        windowY[i] = y < 0 ? lowY : (y >= cells.y ? highY : y);
    }
    vec4 coefficientsY[kBrickRows];
    for (int r = 0; r < kBrickRows; ++r)
        coefficientsY[r] = axisCells[axes.y + min(origin.y + r, cells.y - 1)].coefficients;
    int lowZ = axisCells[axes.z].neighbours.x;
    int highZ = axisCells[axes.z + cells.z - 1].neighbours.y;

    vec4 below[kBrickRows], centre[kBrickRows + 2], above[kBrickRows + 2];
    int belowZ = origin.z > 0 ? origin.z - 1 : lowZ;
    for (int r = 0; r < kBrickRows; ++r)
        below[r] = zero ? vec4(0.0) : rowAt(base, cells, x, windowY[r + 1], belowZ);
    for (int i = 0; i < kBrickRows + 2; ++i)
        centre[i] = zero ? vec4(0.0) : rowAt(base, cells, x, windowY[i], origin.z);
    for (int layer = 0; layer < kBrickLayers; ++layer) {
        int z = origin.z + layer;
        if (z >= cells.z) break;
        int aboveZ = z + 1 < cells.z ? z + 1 : highZ;
        for (int i = 0; i < kBrickRows + 2; ++i)
            above[i] = zero ? vec4(0.0) : rowAt(base, cells, x, windowY[i], aboveZ);
        vec4 coefficientsZ = axisCells[axes.z + z].coefficients;
        for (int r = 0; r < kBrickRows; ++r) {
            int y = origin.y + r;
            if (y >= cells.y) break;
            // A side's area is the product of the other two axes' widths, in the reference's
            // order (axis + 1, axis + 2).
            vec4 cy = coefficientsY[r];
            vec4 areaX = vec4(cy.x * coefficientsZ.x);
            vec4 areaY = coefficientsZ.x * width;
            vec4 areaZ = width * cy.x;
            vec4 cLowX = inverseLowX * areaX, cHighX = inverseHighX * areaX;
            vec4 cLowY = cy.y * areaY, cHighY = cy.z * areaY;
            vec4 cLowZ = coefficientsZ.y * areaZ, cHighZ = coefficientsZ.z * areaZ;
            if (kSolids && level == 0) {
                // A solid cell counts no side; a fluid one no side towards a solid cell (bit 0
                // or bit 1 + s).
                uvec4 bytes = solidBytes(0, elementIndex(cells, x, y, z));
                cLowX = mix(cLowX, vec4(0.0), notEqual(bytes & 3u, uvec4(0u)));
                cHighX = mix(cHighX, vec4(0.0), notEqual(bytes & 5u, uvec4(0u)));
                cLowY = mix(cLowY, vec4(0.0), notEqual(bytes & 9u, uvec4(0u)));
                cHighY = mix(cHighY, vec4(0.0), notEqual(bytes & 17u, uvec4(0u)));
                cLowZ = mix(cLowZ, vec4(0.0), notEqual(bytes & 33u, uvec4(0u)));
                cHighZ = mix(cHighZ, vec4(0.0), notEqual(bytes & 65u, uvec4(0u)));
            }
            vec4 total = cLowX + cHighX + cLowY + cHighY + cLowZ + cHighZ;
            vec4 weighted = vec4(0.0);
            vec4 p = centre[r + 1];
            if (!zero) {
                int rowStart = 4 * (base + elementIndex(cells, 0, y, z));
                float left = vectorCells[rowStart + max(leftIndex, 0)];
                float right = vectorCells[rowStart + max(rightIndex, 0)];
                left = leftIndex >= 0 ? left : 0.0;
                right = rightIndex >= 0 ? right : 0.0;
                vec4 minusX = vec4(left, p.xyz);
                vec4 plusX = mix(vec4(p.yzw, right), vec4(right), plusPast);
                weighted = cLowX * minusX;
                weighted += cHighX * plusX;
                weighted += cLowY * centre[r];
                weighted += cHighY * centre[r + 2];
                weighted += cLowZ * below[r];
                weighted += cHighZ * above[r + 1];
            }
            visitRow(ivec3(x, y, z), elementIndex(cells, x, y, z), p, weighted, total);
        }
        for (int r = 0; r < kBrickRows; ++r)
            below[r] = centre[r + 1];
        for (int i = 0; i < kBrickRows + 2; ++i)
            centre[i] = above[i];
    }
}

#endif
