// The active set's rebuild on the GPU (fluid/sparse_smoke_solver.h, docs/fluid.md "Sparse
// domain"): the resources its passes share. The CPU twin is fluid/sparse_bricks.h (wantSphere,
// wantCell, dilate, commit), which the tests hold the GPU's sets against.
#ifndef MFX_SPARSE_REBUILD_COMMON_GLSL
#define MFX_SPARSE_REBUILD_COMMON_GLSL

#include "fluid_common.glsl"
#include "shared/sparse_fluid.h"

layout(std140, binding = 1) uniform Rebuild {
    SparseRebuildParameters rebuild;
};

const int kBrick = int(MFX_BRICK_SIZE);

ivec3 brickCount() {
    return cellCount() / kBrick;
}
int brickIndex(ivec3 b) {
    ivec3 n = brickCount();
    return b.x + n.x * (b.y + n.y * b.z);
}
ivec3 brickAt(int index) {
    ivec3 n = brickCount();
    return ivec3(index % n.x, (index / n.x) % n.y, index / (n.x * n.y));
}
// The invocation's item of a one-dimensional pass (workgroups of 8x8x4 = 256).
int flatInvocation() {
    return int(gl_WorkGroupID.x * 256u + gl_LocalInvocationIndex);
}

#endif
