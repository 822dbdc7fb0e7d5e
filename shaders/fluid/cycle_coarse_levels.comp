// cycleCoarseLevels: the V-cycle from level `level` down to the coarsest and back, in one
// workgroup: on the coarse levels a dispatch costs more than its work (on a CPU driver some tens
// of microseconds each), so these levels' smoothing, residuals, transfers and coarsest solve run
// as phases of one dispatch, separated by workgroup barriers, each invocation taking every
// (workgroup size)-th brick. Each phase is the function the single-level kernels run
// (shaders/fluid/pressure_multigrid.glsl), so the result is theirs. Twin: Multigrid::cycle in
// fluid/reference/multigrid.cpp (Trottenberg, Oosterlee, Schueller, "Multigrid", 2001, ch. 2;
// McAdams, Sifakis, Teran 2010).
//
// Every level's live correction is its first x (MultigridLevel.vectors.x) on entry and on exit:
// a cycle relaxes each level an even number of half-sweeps.
//
// One workgroup. pc: level (the first level cycled), rhs = its b (the deeper levels' come from
// the restrictions), preSmooth, postSmooth, limit = the number of levels, flags:
// MFX_PRESSURE_ZERO_INPUT (level `level`'s x is 0 on entry). kSymmetric chooses the cycle: the
// multigrid solver's (R0, red-black post-smoothing) or the MGPCG preconditioner's (P^T,
// black-red post-smoothing).
#version 450
#extension GL_GOOGLE_include_directive : require
#define MFX_PRESSURE_COHERENT coherent
#include "pressure_multigrid.glsl"

int groupSize() {
    return int(gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z);
}

// Bricks of a level, and the first element of brick `index` (x fastest).
ivec3 levelBricks(int level) {
    ivec4 cells = levels[level].cells;
    return ivec3(cells.w, (cells.y + kBrickRows - 1) / kBrickRows,
                 (cells.z + kBrickLayers - 1) / kBrickLayers);
}
ivec3 brickOrigin(ivec3 bricks, int index) {
    ivec3 b = ivec3(index % bricks.x, (index / bricks.x) % bricks.y, index / (bricks.x * bricks.y));
    return b * ivec3(1, kBrickRows, kBrickLayers);
}

// The phases of the cycle, in order (each separated from the next by a barrier):
const int kPhaseRelax = 0;    // a half-sweep of level `level`
const int kPhaseResidual = 1; // its residual (unless the restriction computes it)
const int kPhaseRestrict = 2; // onto level `level` + 1
const int kPhaseCoarsest = 3; // the coarsest level's exact solve
const int kPhaseProlong = 4;  // level `level` + 1's correction onto level `level`
struct Phase {
    int kind;
    int level;
    int halfSweep; // kPhaseRelax: which half-sweep of its smoothing
    bool post;     // kPhaseRelax: post-smoothing
};

// The phases per level on the way down: 2 preSmooth half-sweeps, the residual (kResidualPass)
// and the restriction.
int phasesPerLevelDown() {
    return 2 * int(pc.preSmooth) + (kResidualPass ? 2 : 1);
}

// Phase `index` of the cycle from level `first` to the coarsest: per level on the way down
// 2 preSmooth half-sweeps, the residual (kResidualPass) and the restriction; the coarsest
// solve; per level on the
// way up the prolongation and 2 postSmooth half-sweeps. (Decoded rather than written as nested
// loops, so that each operation has one call site: the shader's size, and its compile time, stay
// those of the operations once each.)
Phase phaseAt(int index, int first, int coarsest) {
    int down = phasesPerLevelDown();
    int up = 1 + 2 * int(pc.postSmooth);
    int downPhases = down * (coarsest - first);
    Phase p;
    p.post = false;
    p.halfSweep = 0;
    if (index < downPhases) {
        p.level = first + index / down;
        int i = index % down;
        int relaxPhases = 2 * int(pc.preSmooth);
        p.kind = i < relaxPhases ? kPhaseRelax : (i == down - 1 ? kPhaseRestrict : kPhaseResidual);
        p.halfSweep = i;
    } else if (index == downPhases) {
        p.kind = kPhaseCoarsest;
        p.level = coarsest;
    } else {
        int j = index - downPhases - 1;
        p.level = coarsest - 1 - j / up;
        int i = j % up;
        p.kind = i == 0 ? kPhaseProlong : kPhaseRelax;
        p.halfSweep = i - 1;
        p.post = true;
    }
    return p;
}

void main() {
    int first = pc.level;
    int coarsest = int(pc.limit) - 1;
    int phases = phasesPerLevelDown() * (coarsest - first) + 1 +
                 (1 + 2 * int(pc.postSmooth)) * (coarsest - first);
    int lane = int(gl_LocalInvocationIndex);
    for (int index = 0; index < phases; ++index) {
        Phase p = phaseAt(index, first, coarsest);
        ivec4 x = levels[p.level].vectors;
        int rhs = p.level == first ? pc.rhs : x.z;
        ivec3 bricks = levelBricks(p.kind == kPhaseRestrict ? p.level + 1 : p.level);
        int count = bricks.x * bricks.y * bricks.z;
        if (p.kind == kPhaseCoarsest) {
            for (int i = lane; i < levels[p.level].axisCells.w; i += groupSize())
                solveCoarsestCell(p.level, rhs, x.x, i);
        } else if (p.kind == kPhaseProlong) {
            for (int i = lane; i < count; i += groupSize())
                prolongBrick(p.level, levels[p.level + 1].vectors.x, x.x, brickOrigin(bricks, i));
        } else if (p.kind == kPhaseRestrict) {
            ivec4 coarse = levels[p.level + 1].vectors;
            for (int i = lane; i < count; i += groupSize())
                restrictBrick(p.level, kResidualPass ? x.w : x.x, rhs, coarse.z, coarse.x,
                              brickOrigin(bricks, i));
        } else {
            // A half-sweep (the live x alternates between the level's two, and is the first
            // again after an even count; the smoothing is red-black, the preconditioner's
            // post-smoothing black-red) or the residual r = b - A x.
            bool relax = p.kind == kPhaseRelax;
            bool even = p.halfSweep % 2 == 0;
            visitMode = relax ? kVisitRelax : kVisitResidual;
            visitLevel = p.level;
            visitRhs = rhs;
            visitResult = relax ? (even ? x.y : x.x) : x.w;
            visitColour = even == (p.post && kSymmetric) ? 1 : 0;
            int source = relax && !even ? x.y : x.x;
            bool zero = relax && p.level == first && !p.post && p.halfSweep == 0 &&
                        hasFlag(MFX_PRESSURE_ZERO_INPUT);
            for (int i = lane; i < count; i += groupSize())
                stencilBrick(p.level, source, brickOrigin(bricks, i), zero);
        }
        memoryBarrierBuffer(); // every invocation's writes visible to every other ...
        barrier();             // ... before the next phase
    }
}
