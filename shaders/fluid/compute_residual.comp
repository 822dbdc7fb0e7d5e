// computeResidual: r = b - A p on level `level` of the pressure equation; optionally the partial
// sums of r (for its mean). Twin: PressureGrid::residual in
// fluid/reference/pressure_equation.cpp (the finite-volume operator of Trottenberg, Oosterlee,
// Schueller, "Multigrid", 2001, ch. 2).
//
// pc: level, source = p, rhs = b, result = r, flags: MFX_PRESSURE_PARTIAL_SUMS (level 0 only).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "pressure_multigrid.glsl"
#include "pressure_partial_sums.glsl"

void main() {
    ivec3 origin;
    if (levelBrick(pc.level, origin)) residualBrick(pc.level, pc.source, pc.result, pc.rhs, origin);
    if (hasFlag(MFX_PRESSURE_PARTIAL_SUMS)) writePartialSums(vec4(visitSums.x, 0.0, 0.0, 0.0));
}
