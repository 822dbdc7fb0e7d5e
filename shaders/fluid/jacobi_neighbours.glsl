// The Jacobi pressure sweep's neighbours (docs/fluid.md, step 10): which cell a neighbour index
// reads and whether it counts, shared by solve_pressure.comp and by compute_divergence.comp, which
// can compute a cold start's first sweep (p = -h² div / count) beside the divergence.
#ifndef MFX_JACOBI_NEIGHBOURS_GLSL
#define MFX_JACOBI_NEIGHBOURS_GLSL

// A neighbour coordinate i (at most one step outside 0..n-1, or anywhere past n - 1 for a cell
// beyond the grid's last one) along `axis`: the cell to read, whether its value counts and
// whether it counts in the divisor (open faces: ghost p = 0; walls are not counted; periodic
// faces wrap). Branch-free.
struct NeighbourRef {
    int index;
    bool value;
    bool counted;
};

NeighbourRef neighbourRef(int axis, int i) {
    int n = cellCount()[axis];
    bool high = i >= n;
    uint kind = boundaryKind(axis, high);
    bool inside = i >= 0 && !high;
    bool periodic = kind == MFX_BOUNDARY_PERIODIC;
    int wrapped = periodic ? wrapIndex(i, n) : i;
    NeighbourRef ref;
    ref.index = clamp(wrapped, 0, n - 1);
    ref.value = inside || periodic;
    ref.counted = inside || periodic || kind == MFX_BOUNDARY_OPEN;
    return ref;
}

// The neighbours cell q's sweep divides by.
int jacobiNeighbourCount(ivec3 q) {
    int count = 0;
    for (int axis = 0; axis < 3; ++axis) {
        count += neighbourRef(axis, q[axis] - 1).counted ? 1 : 0;
        count += neighbourRef(axis, q[axis] + 1).counted ? 1 : 0;
    }
    return count;
}

// Element of row (y, z)'s four cells 4 texel .. 4 texel + 3 in a packed buffer (solve_pressure.comp:
// four x-consecutive cells per vec4, rows padded to a whole vec4).
int packedIndex(int texel, int y, int z) {
    return texel + ((cellCount().x + 3) / 4) * (y + cellCount().y * z);
}

#endif
