// The active set's rebuild, 2: every brick an emitter's sphere reaches is wanted, the part outside
// the domain cut off; emitters with a non-finite centre or radius, or a radius <= 0, mark nothing.
// One invocation an emitter. Twin: SparseBricks::wantSphere (the same box test, in cells).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "sparse_rebuild_common.glsl"

layout(std430, binding = 2) readonly buffer Emitters {
    FluidEmitter emitters[];
};
layout(std430, binding = 3) buffer Wanted {
    uint wanted[];
};

void main() {
    int i = flatInvocation();
    if (i >= int(min(params.size.w, uint(emitters.length())))) return;
    vec4 sphere = emitters[i].positionRadius;
    if (any(isnan(sphere)) || any(isinf(sphere)) || !(sphere.w > 0.0)) return;
    vec3 centre = sphere.xyz / cellSize();
    float radius = sphere.w / cellSize();
    float b = float(kBrick);
    vec3 extent = vec3(brickCount()) * b;
    if (any(lessThan(centre + radius, vec3(0.0))) || any(greaterThanEqual(centre - radius, extent)))
        return;
    vec3 top = vec3(brickCount()) - 1.0;
    ivec3 low = ivec3(clamp(floor((centre - radius) / b), vec3(0.0), top));
    ivec3 high = ivec3(clamp(floor((centre + radius) / b), vec3(0.0), top));
    for (int z = low.z; z <= high.z; ++z)
        for (int y = low.y; y <= high.y; ++y)
            for (int x = low.x; x <= high.x; ++x) {
                vec3 boxLow = vec3(x, y, z) * b;
                vec3 d = clamp(centre, boxLow, boxLow + b) - centre;
                if (dot(d, d) <= radius * radius)
                    wanted[brickIndex(ivec3(x, y, z))] = MFX_BRICK_WANTED;
            }
}
