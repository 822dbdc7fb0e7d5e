// Dense optical flow between two pictures of a flipbook (render/flipbook.h): the motion vectors a
// bake measures from its own frames ("flow"), for any effect. The method is Horn and Schunck's
// ("Determining Optical Flow", Artificial Intelligence 17, 1981): the flow u minimising
//     sum over pixels and channels c of (Ix_c du + Iy_c dv + It_c)^2 + alpha^2 |grad u|^2,
// the brightness-constancy term linearised about the current flow (eq. 7 to 9 there, here summed
// over the four premultiplied channels), solved by Jacobi iterations in which each pixel's flow
// is the 2x2 solve against the mean of its four neighbours (their eq. 12 to 14 for one channel).
// Coarse to fine with warping, as Brox et al. ("High accuracy optical flow estimation based on a
// theory for warping", ECCV 2004) do, so that motion of many pixels is found: a pyramid halving
// each level down to about 16 pixels, the coarser level's flow doubled and interpolated as the
// start of the finer, the second picture warped back by the flow before each linearisation.
#pragma once

#include "render/flipbook.h"

namespace mfx::render {

struct FlowOptions {
    float smoothness = 0.8f;  // alpha, in the pictures' units per pixel (their values in [0, 1])
    uint32_t warps = 3;       // linearisations per level
    uint32_t iterations = 60; // Jacobi iterations per linearisation
    uint32_t coarsest = 16;   // the pyramid stops above this many pixels on the shorter side
};

// The motion (in pixels, x right, y down) that takes `from`'s content to where it is in `to`
// (the same size): to(p + flow(p)) ~ from(p).
MotionField opticalFlow(const CellImage& from, const CellImage& to,
                        const FlowOptions& options = {});

} // namespace mfx::render
