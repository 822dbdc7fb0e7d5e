// applyPressureOperator: q = A d on level 0, and the partial sums of (d, q): the first half of a
// conjugate gradient iteration. Twin: PressureGrid::apply in
// fluid/reference/pressure_equation.cpp, as solvePressureMgpcg uses it (fluid/reference/mgpcg.cpp;
// Saad, "Iterative Methods for Sparse Linear Systems", 2003, alg. 9.1).
//
// pc: source = d, result = q.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "pressure_multigrid.glsl"
#include "pressure_partial_sums.glsl"

void main() {
    ivec3 origin;
    if (levelBrick(0, origin)) applyBrick(pc.source, pc.result, origin);
    writePartialSums(vec4(visitSums.x, 0.0, 0.0, 0.0));
}
