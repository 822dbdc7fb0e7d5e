// relaxColour: one half-sweep of red-black Gauss-Seidel on level `level` of the pressure
// equation A p = b: every cell of colour `step` (0 red: i + j + k even, 1 black) takes
//   p_q <- (sum_s c_s p_n(s) + b_q) / sum_s c_s   (0 where nothing is counted),
// reading the values as they stood before the half-sweep; the other colour is copied (see
// relaxBrick in shaders/fluid/pressure_multigrid.glsl). Twin: PressureGrid::relaxColour in
// fluid/reference/red_black_gauss_seidel.cpp (Trottenberg, Oosterlee, Schueller, "Multigrid",
// 2001, ch. 2).
//
// pc: level, source = p before, result = p after, rhs = b, step = colour,
// flags: MFX_PRESSURE_ZERO_INPUT (p before is 0).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "pressure_multigrid.glsl"

void main() {
    ivec3 origin;
    if (!levelBrick(pc.level, origin)) return;
    relaxBrick(pc.level, pc.source, pc.result, pc.rhs, int(pc.step),
               hasFlag(MFX_PRESSURE_ZERO_INPUT), origin);
}
