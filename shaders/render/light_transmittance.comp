// The key light's transmittance through the smoke, once per frame and volume, for the march to
// fetch once per view sample (smoke_march.glsl) instead of marching towards the light from each. The
// volume spans the pigment's box (the box smoke.vert draws: the cells holding pigment, grown by
// one), one texel a cell of it from the image's low corner (lightTexels(): a box wider than the
// image shares texels between cells; the image has room for the grid's cells, at most
// SmokeLook::maxLightCells a side). Texels past the box and its one extra layer are not written,
// and the march's fetches stay inside the box, so the work follows the box, not the grid. At the
// centre p of each of its cells, T_l = exp(-integral of density towards the light), integrated by
// the midpoint rule in steps of at most one grid cell from p to where its ray towards the light
// leaves the box, so the whole depth of smoke shadows (no pigment lies outside the box). Single
// scattering with self-shadowing as in Fedkiw, Stam and Jensen, "Visual Simulation of Smoke"
// (SIGGRAPH 2001), section 4, which also first stores the light reaching each voxel and then
// marches the view rays.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/smoke_draw.h"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(push_constant) uniform Draw {
    SmokeDraw draw; // gridOrigin, gridSize (xyz) and light (towards it; w: density scale)
};

#ifdef MFX_SPARSE_PIGMENT
#include "shared/sparse_fluid.h"
layout(std430, binding = 0) readonly buffer PigmentAtlas {
    vec4 atlas[];
};
layout(std430, binding = 4) readonly buffer BrickTable {
    uint brickSlot[];
};
#else
layout(binding = 0) uniform sampler3D pigment;
#endif
layout(std430, binding = 2) readonly buffer Bounds {
    PigmentBounds bounds;
};
layout(binding = 5, r32f) uniform writeonly image3D transmittance;

#include "smoke_sampling.glsl"

#include "smoke_light.glsl"

// Steps of one light march: one a grid cell across the largest box the domain allows (2048 cells
// a side: a diagonal of 3548 cells).
const int kMaxSteps = 3584;

void main() {
    ivec3 t = ivec3(gl_GlobalInvocationID);
    ivec3 size = imageSize(transmittance);
    if (any(greaterThanEqual(t, size))) return;
    // An empty box shadows nothing (and the march draws nothing).
    if (bounds.low.x > bounds.high.x) {
        imageStore(transmittance, t, vec4(1.0));
        return;
    }
    vec3 cells = draw.gridSize.xyz;
    float h = draw.gridOrigin.w;
    vec3 low = max(vec3(bounds.low.xyz) - 1.0, vec3(0.0));
    vec3 high = min(vec3(bounds.high.xyz) + 2.0, cells);
    vec3 used = lightTexels(high - low, vec3(size));
    // The texels of the box, and the layer beyond its high sides, which repeats the box's last
    // texels: a fetch at the box's high face filters halfway into it, as the image's own edge
    // clamps. Texels further out are never fetched (smoke_march.glsl clamps its fetches to the box).
    if (any(greaterThan(vec3(t), used))) return;
    vec3 boxLow = draw.gridOrigin.xyz + h * low, boxHigh = draw.gridOrigin.xyz + h * high;
    vec3 p = mix(boxLow, boxHigh, (min(vec3(t), used - 1.0) + 0.5) / used);
    vec3 light = normalize(draw.light.xyz);
    // An axis the light runs across has no exit along it (a large t, not 0 * inf).
    vec3 lightInv = 1.0 / mix(light, vec3(1e-6), lessThan(abs(light), vec3(1e-6)));
    vec3 t0 = (boxLow - p) * lightInv, t1 = (boxHigh - p) * lightInv;
    vec3 far = max(t0, t1);
    float reach = max(min(min(far.x, far.y), far.z), 0.0);
    int steps = clamp(int(ceil(reach / h)), 1, kMaxSteps);
    float ds = reach / float(steps);
    float optical = 0.0;
    for (int k = 0; k < steps; ++k)
        optical += max(sampleGrid(p + light * ((float(k) + 0.5) * ds)).a, 0.0);
    imageStore(transmittance, t, vec4(exp(-optical * draw.light.w * ds)));
}
