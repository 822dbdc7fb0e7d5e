// Moving solids on the sparse grid (docs/fluid.md, "Solids" and "Sparse domain"), as its stages
// read them: per stored cell, in the atlas's cell layout (shaders/shared/sparse_fluid.h), the
// index + 1 of the first solid in list order holding its centre, 0 for air
// (sparse_mark_solids.comp writes them at the start of each sub-step). A cell that is not stored
// is air: what is not stored is air at rest (the active set holds every brick the solids reach,
// SparseSmokeSolver::recordRebuild). Twin: fluid/reference/mark_solids.cpp with the reference's
// active cells. Without solids (kSparseSolids false, constant id 12) every test below folds to
// false and a stage is the one it was before solids existed.
#ifndef MFX_SPARSE_SOLIDS_GLSL
#define MFX_SPARSE_SOLIDS_GLSL

#include "sparse_common.glsl"

layout(constant_id = 12) const bool kSparseSolids = false;

layout(std430, binding = 14) buffer SolidHolders {
    uint solidHolders[];
};

// Whether the stored cell at atlas element e (-1: not stored) is solid.
bool solidElement(int e) {
    return kSparseSolids && e >= 0 && solidHolders[e] != 0u;
}

// Whether cell q is solid (cells outside the domain and not stored are not).
bool sparseSolidCell(ivec3 q) {
    if (!kSparseSolids || any(lessThan(q, ivec3(0))) || any(greaterThanEqual(q, cellCount())))
        return false;
    return solidElement(cellElementAt(q));
}

// Whether face q of component c is solid: a cell beside it is, and it is not wall-normal (a wall
// stays a wall).
bool sparseSolidFace(int c, ivec3 q) {
    if (!kSparseSolids || wallNormalFace(c, q)) return false;
    ivec3 below = q;
    below[c] -= 1;
    return sparseSolidCell(below) || sparseSolidCell(q);
}

#endif
