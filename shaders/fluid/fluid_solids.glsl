// Moving solids in the grid (docs/fluid.md, "Solids"), as the stages read them: the solid cells of
// the sub-step, marked by shaders/fluid/mark_solids.comp into one uvec2 per cell (x-fastest):
//   x  the first solid (1-based, in the list's order) holding the cell's centre; 0 for air
//   y  bit s set when the cell's neighbour on side s (-x, +x, -y, +y, -z, +z) is a solid cell
//      (a neighbour inside the grid, or across a periodic face)
// Twin: fluid/reference/mark_solids.cpp. Without solids (kSolids false, constant id 15) every test
// below folds to false and a stage is the one it was before solids existed.
#ifndef MFX_FLUID_SOLIDS_GLSL
#define MFX_FLUID_SOLIDS_GLSL

layout(constant_id = 15) const bool kSolids = false;

#ifdef MFX_MARKS_SOLIDS
layout(std430, binding = 15) buffer SolidCells {
    uvec2 solidCells[];
};
#else
layout(std430, binding = 15) readonly buffer SolidCells {
    uvec2 solidCells[];
};
#endif

// Whether cell q (inside the grid) is solid.
bool solidCell(ivec3 q) {
    return kSolids && solidCells[cellElement(q)].x != 0u;
}

// Cell q - e_c and cell q of face q of component c, those that exist (out of the grid across a
// non-periodic face: none), wrapped across periodic faces.
bool solidBelowFace(int c, ivec3 q) {
    ivec3 below = q;
    below[c] -= 1;
    if (below[c] < 0) {
        if (!periodicAxis(c)) return false;
        below[c] = cellCount()[c] - 1;
    }
    return solidCell(below);
}
bool solidAboveFace(int c, ivec3 q) {
    if (q[c] >= cellCount()[c]) {
        if (!periodicAxis(c)) return false;
        q[c] = 0;
    }
    return solidCell(q);
}

// Whether face q of component c is solid: a cell beside it is, and it is not wall-normal (a wall
// stays a wall).
bool solidFace(int c, ivec3 q) {
    if (!kSolids || wallNormalFace(c, q)) return false;
    return solidBelowFace(c, q) || solidAboveFace(c, q);
}

// The six sides' solid-neighbour bits of cell q (inside the grid), in the order above.
uint solidNeighbours(ivec3 q) {
    return kSolids ? solidCells[cellElement(q)].y : 0u;
}

#endif
