// How the smoke pass reads a pigment volume at a world position (the march, smoke_march.glsl, and the
// light's transmittance, light_transmittance.comp): trilinear between cell centres, 0 outside the
// grid. A dense grid's pigment is a sampler3D; with MFX_SPARSE_PIGMENT a sparse grid's atlas and
// brick table (fluid/sparse_smoke_solver.h), sampled by hand from the eight cells, 0 where no
// brick is stored, as the solver reads them. The including shader declares `draw` (SmokeDraw) and
// the bindings: `pigment`, or `atlas` and `brickSlot`.
#ifndef MFX_SMOKE_SAMPLING_GLSL
#define MFX_SMOKE_SAMPLING_GLSL

#ifdef MFX_SPARSE_PIGMENT
// The slot of brick b, or MFX_NO_SLOT (not stored, or outside the domain).
uint slotOf(ivec3 b) {
    ivec3 n = ivec3(draw.gridSize.xyz) / int(MFX_BRICK_SIZE);
    if (any(lessThan(b, ivec3(0))) || any(greaterThanEqual(b, n))) return MFX_NO_SLOT;
    return brickSlot[b.x + n.x * (b.y + n.y * b.z)];
}

vec4 cellPigment(ivec3 q) {
    uint slot = slotOf(q >> 3);
    if (slot == MFX_NO_SLOT) return vec4(0.0);
    ivec3 l = q & 7;
    return atlas[slot * MFX_BRICK_CELLS + uint(l.x + 8 * (l.y + 8 * l.z))];
}

// Trilinear between cell centres, as the dense image's sampler. When the eight cells lie in one
// brick (about two samples in three), its slot is looked up once.
vec4 sampleGrid(vec3 world) {
    vec3 g = (world - draw.gridOrigin.xyz) / draw.gridOrigin.w - 0.5;
    ivec3 q = ivec3(floor(g));
    vec3 f = g - vec3(q);
    vec4 c[8];
    ivec3 l = q & 7;
    if (all(lessThan(l, ivec3(7))) && all(greaterThanEqual(q, ivec3(0)))) {
        uint slot = slotOf(q >> 3);
        if (slot == MFX_NO_SLOT) return vec4(0.0);
        uint base = slot * MFX_BRICK_CELLS + uint(l.x + 8 * (l.y + 8 * l.z));
        for (int k = 0; k < 8; ++k)
            c[k] = atlas[base + uint((k & 1) + 8 * ((k >> 1) & 1) + 64 * (k >> 2))];
    } else {
        for (int k = 0; k < 8; ++k)
            c[k] = cellPigment(q + ivec3(k & 1, (k >> 1) & 1, k >> 2));
    }
    vec4 x00 = mix(c[0], c[1], f.x), x10 = mix(c[2], c[3], f.x);
    vec4 x01 = mix(c[4], c[5], f.x), x11 = mix(c[6], c[7], f.x);
    return mix(mix(x00, x10, f.y), mix(x01, x11, f.y), f.z);
}

#else
vec4 sampleGrid(vec3 world) {
    vec3 uvw = (world - draw.gridOrigin.xyz) / (draw.gridOrigin.w * draw.gridSize.xyz);
    return texture(pigment, uvw);
}
#endif

#endif
