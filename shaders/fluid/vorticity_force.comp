// vorticityConfinement's first two passes in one, for the direct store path (a GPU): each
// workgroup computes omega = curl u (compute_vorticity.comp's formula, eq. 9) for its block of cells
// and the ring of cells around it into shared memory, then the confinement force f = epsilon h
// (N x omega), N = grad|omega| / |grad|omega|| (confinement_force.comp's formula, eqs. 10-11) of its
// block from there, and stores f into the force image. The vorticity field is never written or
// read back: the same values as the two passes, bit for bit, with one dispatch and one barrier
// fewer and 32 bytes a cell less to move. A ring cell outside the grid holds the vorticity of the
// cell the force pass would have fetched there (resolveCell: clamped, or wrapped on a periodic
// axis). Fedkiw, Stam, Jensen, "Visual Simulation of Smoke" (SIGGRAPH 2001), eqs. 9-11; twin:
// fluid/reference/vorticity_confinement.cpp.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityX;
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityY;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityZ;
layout(binding = 4, rgba32f) uniform writeonly image3D forceImage;

// The workgroup's block and its ring, x fastest.
const uvec3 kTile = gl_WorkGroupSize + uvec3(2u);
shared vec4 omega[kTile.x * kTile.y * kTile.z];

float fetchVelocity(int c, ivec3 index) {
    FaceRef r = resolveFace(c, index);
    float raw = c == 0
                    ? imageLoad(velocityX, r.index).r
                    : (c == 1 ? imageLoad(velocityY, r.index).r : imageLoad(velocityZ, r.index).r);
    return r.scale * raw + r.offset;
}

// Cell-centred velocity component c of a possibly out-of-range cell.
float centred(int c, ivec3 q) {
    ivec3 hi = q;
    hi[c] += 1;
    return 0.5 * (fetchVelocity(c, q) + fetchVelocity(c, hi));
}

// omega and |omega| at cell q (inside the grid), as compute_vorticity.comp computes them.
vec4 vorticityAt(ivec3 q) {
    const ivec3 ex = ivec3(1, 0, 0), ey = ivec3(0, 1, 0), ez = ivec3(0, 0, 1);
    float inv2h = 1.0 / (2.0 * cellSize());
    vec3 w = vec3(
        (centred(2, q + ey) - centred(2, q - ey) - centred(1, q + ez) + centred(1, q - ez)) * inv2h,
        (centred(0, q + ez) - centred(0, q - ez) - centred(2, q + ex) + centred(2, q - ex)) * inv2h,
        (centred(1, q + ex) - centred(1, q - ex) - centred(0, q + ey) + centred(0, q - ey)) *
            inv2h);
    return vec4(w, length(w));
}

vec4 tileAt(ivec3 l) {
    return omega[l.x + int(kTile.x) * (l.y + int(kTile.y) * l.z)];
}

void main() {
    ivec3 corner = ivec3(gl_WorkGroupID * gl_WorkGroupSize) - 1;
    uint count = kTile.x * kTile.y * kTile.z;
    uint invocations = gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z;
    for (uint i = gl_LocalInvocationIndex; i < count; i += invocations) {
        ivec3 l = ivec3(i % kTile.x, (i / kTile.x) % kTile.y, i / (kTile.x * kTile.y));
        // Ring cells past the grid's last one + 1 are never read; held at it, so that a short
        // periodic axis wraps them inside the grid (wrapIndex takes less than three lengths).
        omega[i] = vorticityAt(resolveCell(min(corner + l, cellCount())));
    }
    barrier();
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(q, cellCount()))) return;
    ivec3 l = ivec3(gl_LocalInvocationID) + 1;
    const ivec3 ex = ivec3(1, 0, 0), ey = ivec3(0, 1, 0), ez = ivec3(0, 0, 1);
    float inv2h = 1.0 / (2.0 * cellSize());
    vec4 w = tileAt(l);
    vec3 eta = vec3((tileAt(l + ex).w - tileAt(l - ex).w) * inv2h,
                    (tileAt(l + ey).w - tileAt(l - ey).w) * inv2h,
                    (tileAt(l + ez).w - tileAt(l - ez).w) * inv2h);
    // Regularised normalisation: where |omega| barely varies there is nothing to confine.
    vec3 n = eta / (length(eta) + 1e-3 * w.w * inverseCellSize() + 1e-20);
    imageStore(forceImage, q, vec4(params.rates.z * cellSize() * cross(n, w.xyz), 0.0));
}
