// restrictResidual: the right-hand side of level `level` + 1 from the residual of level `level`,
// by R0 (each coarse cell sums the residuals of the fine cells it covers, read from the residual
// compute_residual wrote or, kResidualInRestriction, computed here from p and b: the multigrid
// solver's V-cycle) or by P^T (of the residual compute_residual wrote) (each fine residual goes to the coarse cells it is interpolated from, with
// the interpolation weights: the MGPCG preconditioner's); the coarse correction starts at 0 (see
// shaders/fluid/pressure_multigrid.glsl). Twin: Multigrid::restrictSum and Multigrid::restrictTranspose
// in fluid/reference/multigrid.cpp (Trottenberg et al. 2001, ch. 2; McAdams, Sifakis, Teran
// 2010).
//
// One invocation per brick of the coarse level. pc: level (the fine one), source = the fine
// residual or, kResidualInRestriction, p, rhs = the fine b (kResidualInRestriction), result =
// coarse b, other = coarse correction; kSymmetric: P^T, else R0.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "pressure_multigrid.glsl"

void main() {
    ivec3 origin;
    if (!levelBrick(pc.level + 1, origin)) return;
    restrictBrick(pc.level, pc.source, pc.rhs, pc.result, pc.other, origin);
}
