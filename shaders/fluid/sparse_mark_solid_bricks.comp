// The active set's rebuild, 3b (after the dilation, into the brick states): every brick a solid
// may reach is wanted, so that the body's cells are stored and the air it pushes is simulated
// (docs/fluid.md, "Solids" and "Sparse domain"): a brick whose cell centres' bounding sphere (its
// centre, 3.5 √3 cells wide, and a hundredth of a cell) meets the capsule. Not grown by the
// advection's reach: the air the body stirs is live, and the next rebuild grows its bricks. One
// invocation a solid (rebuild.counts.w of them). Twin: SparseBricks::wantCapsule (the same test,
// in cells).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_rebuild_common.glsl"

layout(std140, binding = 2) uniform Solids {
    FluidSolid solids[1024];
};
layout(std430, binding = 3) buffer Wanted {
    uint wanted[];
};

void main() {
    int i = flatInvocation();
    if (i >= int(min(rebuild.counts.w, 1024u))) return;
    FluidSolid s = solids[i];
    // In cells: a cell's centre is at its index + 0.5.
    vec3 a = s.endA.xyz / cellSize(), b = s.endB.xyz / cellSize();
    float reach = s.endA.w / cellSize() + 3.5 * sqrt(3.0) + 0.01;
    float size = float(kBrick);
    vec3 top = vec3(brickCount()) - 1.0;
    vec3 low = min(a, b) - reach, high = max(a, b) + reach;
    if (any(lessThan(high, vec3(0.0))) || any(greaterThanEqual(low, vec3(brickCount()) * size)))
        return;
    ivec3 first = ivec3(clamp(floor(low / size), vec3(0.0), top));
    ivec3 last = ivec3(clamp(floor(high / size), vec3(0.0), top));
    vec3 ab = b - a;
    float length2 = dot(ab, ab);
    for (int z = first.z; z <= last.z; ++z)
        for (int y = first.y; y <= last.y; ++y)
            for (int x = first.x; x <= last.x; ++x) {
                vec3 centre = vec3(x, y, z) * size + 0.5 * size;
                float t = length2 > 0.0 ? clamp(dot(centre - a, ab) / length2, 0.0, 1.0) : 0.0;
                vec3 d = centre - (a + t * ab);
                if (dot(d, d) <= reach * reach) wanted[brickIndex(ivec3(x, y, z))] = MFX_BRICK_WANTED;
            }
}
