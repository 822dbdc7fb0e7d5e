// prolongCorrection: p += P e on level `level`, P the trilinear interpolation of the correction e
// of level `level` + 1 at each fine cell centre (see prolongBrick in
// shaders/fluid/pressure_multigrid.glsl). Twin: Multigrid::prolong in fluid/reference/multigrid.cpp
// (Trottenberg et al. 2001, ch. 2).
//
// pc: level (the fine one), source = coarse correction e, result = fine p (updated in place).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "pressure_multigrid.glsl"

void main() {
    ivec3 origin;
    if (levelBrick(pc.level, origin)) prolongBrick(pc.level, pc.source, pc.result, origin);
}
