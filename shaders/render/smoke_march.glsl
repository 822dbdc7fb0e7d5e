// The smoke pass's march: a ray from the camera through a texel of the fluid buffer marches the
// pigment volume (front to back, trilinear samples), with light absorption towards the key light
// so the smoke has shape, and stops at the scene's depth, fading smoke behind the scene surface it
// meets by how far behind it lies (DESIGN.md "Formulas": alpha *= saturate(1 - (D_fluid -
// D_scene) / b)), so smoke meets the floor and the character softly. Pigment is RGBA with rgb =
// colour x alpha; density = alpha x scale.
//
// Run by a fragment shader over the box's faces (smoke.frag, on a CPU device) or by a compute
// shader over the whole fluid buffer (smoke_march.comp, on a GPU); the SmokeLook's `march` chooses
// (render/smoke_pass.h). Both call march() below for a texel whose ray meets the box.
//
// The fluid buffer has 1 / kDivisor of the picture's width and height (a half-resolution fluid
// buffer, as the spec allows); smoke_composite.frag lays it over the picture. Each texel writes its
// premultiplied colour and alpha, and the scene distance it marched to: that of one pixel of its
// kDivisor x kDivisor block, the nearest on one colour of a checkerboard and the farthest on the
// other, so that along a silhouette both the near and the far surface have texels marched for
// them (the checkerboard min/max depth downsample common in mixed-resolution rendering).
//
// Shading (the volume's SmokeStyle, scene::SmokeShading): single scattering. Each sample, of
// opacity a = 1 - exp(-density ds), seen through the transmittance T_v of the samples before it,
// scatters the key light (its colour and intensity L) towards the eye:
//   colour += T_v a (albedo L (kAmbient + (1 - kAmbient) T_l p(cos theta)) + emitted),
// where T_l = exp(-integral of density towards the light) is the light's transmittance to the
// sample (self-shadowing): one trilinear fetch from the transmittance volume that
// light_transmittance.comp marched for this frame over the pigment's box (at the grid's
// resolution, each cell marched to where its ray towards the light leaves the box, so the whole
// depth of smoke shadows);
// p is the Henyey-Greenstein phase function normalised to 1 for even scattering,
//   p = (1 - g^2) / (1 + g^2 - 2 g cos theta)^(3/2),  cos theta = dot(towards the light, ray),
// with the style's anisotropy g (forwards scattering makes smoke between the eye and the light
// glow); kAmbient of the light reaches every sample unshadowed (the sky). With cel bands, T_l is
// stepped. The albedo is the pigment's colour (smoke) or the preset's ramp at the sample's pigment
// alpha (fire, energy), and fire and energy add their own light, glow * ramp * alpha (fire: hotter
// where denser), which may exceed 1: the bloom spreads it.
//
// The ray is marched only inside the box of cells that hold pigment (pigmentBox, as smoke.vert), with
// its samples at the same places as a march over the whole grid would put them, so the box moving
// from frame to frame does not move the samples.
//
// Built twice: for a dense grid's pigment image (a sampler3D, trilinear, 0 outside), and with
// MFX_SPARSE_PIGMENT for a sparse grid (fluid/sparse_smoke_solver.h): the pigment atlas and the
// brick table as storage buffers, the trilinear sample taken by hand from the eight cells (0 where
// no brick is stored, as the solver reads them), and the march skipping empty bricks: a sample
// whose point lies inside an unstored brick, at least half a cell from its sides, reads only that
// brick's cells, so it is 0; the march jumps past every such sample at once, to the first beyond
// the brick's inner box. What it skips is exactly what it would have added (nothing); the
// samples it takes are the dense march's.
#ifndef MFX_SMOKE_MARCH_GLSL
#define MFX_SMOKE_MARCH_GLSL

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
layout(binding = 1) uniform sampler2D sceneDepth;
layout(binding = 5) uniform sampler3D lightVolume; // T_l over the box (light_transmittance.comp)

#include "smoke_common.glsl"

layout(std140, binding = 3) uniform Style {
    SmokeStyle style;
};


#include "smoke_sampling.glsl"

#ifdef MFX_SPARSE_PIGMENT
// The last sample index whose point is still inside the inner box of the unstored brick holding
// p (the brick shrunk by half a cell: its samples read that brick's cells alone), or `i` where p
// is not in such a box. Sample k lies at t = gridEnter + (k + 0.5) step.
int lastEmptySample(int i, vec3 p, vec3 inv, float gridEnter, float step) {
    vec3 g = (p - draw.gridOrigin.xyz) / draw.gridOrigin.w;
    ivec3 b = ivec3(floor(g / float(MFX_BRICK_SIZE)));
    if (slotOf(b) != MFX_NO_SLOT) return i; // (a brick outside the domain has none: it reads 0)
    vec3 low = vec3(b * int(MFX_BRICK_SIZE)) + 0.5;
    vec3 high = low + float(MFX_BRICK_SIZE) - 1.0;
    if (any(lessThan(g, low)) || any(greaterThan(g, high))) return i;
    vec3 world0 = draw.gridOrigin.xyz + draw.gridOrigin.w * low;
    vec3 world1 = draw.gridOrigin.xyz + draw.gridOrigin.w * high;
    float leave = crossBox(inv, world0, world1).y;
    return max(i, int(floor((leave - gridEnter) / step - 0.5)));
}
#endif

// The ramp at x, piecewise linear. No branch here or below reads the style's buffer (lavapipe
// compiles a shader variant for each value a uniform-buffer branch takes): each step moves towards
// the next stop by how far x is past the previous one, and the switches are mixes.
vec3 rampAt(float x) {
    vec3 c = style.ramp[0].rgb;
    for (int i = 1; i < 4; ++i) {
        float a = style.ramp[i - 1].w, b = style.ramp[i].w;
        c = mix(c, style.ramp[i].rgb, b > a ? clamp((x - a) / (b - a), 0.0, 1.0) : step(a, x));
    }
    return c;
}

const float kAmbient = 0.35;

// Henyey-Greenstein, 1 for g = 0.
float phase(float g, float cosTheta) {
    return (1.0 - g * g) / pow(max(1.0 + g * g - 2.0 * g * cosTheta, 1e-4), 1.5);
}

#include "smoke_light.glsl"

// The light's transmittance to p, from the volume marched for this frame over the pigment's box.
float lightTransmittance(vec3 p) {
    vec3 size = vec3(textureSize(lightVolume, 0));
    vec3 used = lightTexels(round((boxHigh - boxLow) / draw.gridOrigin.w), size);
    // Clamped to the box: the march's last sample may lie past it (at most half a step).
    vec3 inBox = clamp((p - boxLow) / (boxHigh - boxLow), 0.0, 1.0);
    return texture(lightVolume, inBox * (used / size)).r;
}

// The scene pixel of `texel`'s block of kDivisor x kDivisor pixels with the nearest (or, not
// `nearest`, the farthest) depth.
ivec2 blockPixel(ivec2 texel, bool nearest) {
    ivec2 size = textureSize(sceneDepth, 0);
    ivec2 chosen = min(texel * kDivisor, size - 1);
    float chosenDepth = texelFetch(sceneDepth, chosen, 0).r;
    for (int k = 1; k < kDivisor * kDivisor; ++k) {
        ivec2 pixel = min(texel * kDivisor + ivec2(k % kDivisor, k / kDivisor), size - 1);
        float depth = texelFetch(sceneDepth, pixel, 0).r;
        if (nearest ? depth < chosenDepth : depth > chosenDepth) {
            chosen = pixel;
            chosenDepth = depth;
        }
    }
    return chosen;
}

// The march of the ray through `texel`'s centre (its colour), and the scene distance it marched to.
vec4 march(ivec2 texel, vec3 dir, out float marched) {
    // The scene pixel of this texel's block it marches to.
    float sceneDistance = sceneDistanceAt(blockPixel(texel, ((texel.x + texel.y) & 1) == 0));
    vec3 eye = draw.eye.xyz;
    vec3 inv = 1.0 / dir;
    vec2 box = crossBox(inv, boxLow, boxHigh);
    marched = marchedDistance(sceneDistance);
    // Samples are spaced from where the ray enters the whole grid; only those inside the pigment's
    // box and before the faded-out scene surface are taken.
    vec3 gridLow = draw.gridOrigin.xyz;
    float gridEnter = crossBox(inv, gridLow, gridLow + draw.gridOrigin.w * draw.gridSize.xyz).x;
    float fade = fadeDistance();
    float tExit = min(box.y, sceneDistance + fade);
    if (tExit <= box.x) return vec4(0.0);
    float step = draw.gridOrigin.w / max(draw.gridSize.w, 0.25);
    int first = max(int((box.x - gridEnter) / step), 0);
    int end = min(int((tExit - gridEnter) / step) + 1, first + 512);
    vec3 light = normalize(draw.light.xyz);
    float scale = draw.light.w;
    float scatter = phase(style.light.w, dot(light, dir));
    vec3 colour = vec3(0.0);
    float transmittance = 1.0;
    for (int i = first; i < end && transmittance > 0.01; ++i) {
        float t = gridEnter + (float(i) + 0.5) * step;
        vec3 p = eye + t * dir;
#ifdef MFX_SPARSE_PIGMENT
        int last = lastEmptySample(i, p, inv, gridEnter, step);
        if (last > i) {
            i = last; // samples i..last read an empty brick alone: 0
            continue;
        }
#endif
        vec4 s = sampleGrid(p);
        float density = max(s.a, 0.0) * scale;
        if (density <= 1e-5) continue;
        // Behind the scene surface by d: faded linearly to nothing at d = b.
        float visible = clamp(1.0 - (t - sceneDistance) / fade, 0.0, 1.0);
        float a = (1.0 - exp(-density * step)) * visible;
        float lit = lightTransmittance(p);
        float bands = max(style.params.y, 1.0);
        lit = mix(lit, floor(lit * bands + 0.5) / bands, float(style.params.y > 0.5));
        float density01 = clamp(s.a, 0.0, 1.0);
        float ramped = float(style.params.w > 0.5); // fire or energy
        vec3 ramp = rampAt(density01);
        vec3 albedo = mix(s.rgb / max(s.a, 1e-4), ramp, ramped);
        vec3 keyLight = style.light.rgb * style.params.z;
        vec3 emitted = ramped * style.params.x * ramp * density01;
        colour += transmittance * a *
                  (albedo * keyLight * (kAmbient + (1.0 - kAmbient) * lit * scatter) + emitted);
        transmittance *= 1.0 - a;
    }
    return vec4(colour, 1.0 - transmittance);
}

#ifdef MFX_SMOKE_CARTOON
#include "smoke_cartoon.glsl"
#endif

#endif
