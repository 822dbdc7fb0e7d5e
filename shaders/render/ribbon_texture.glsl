// A speed-line's texture (scene::RibbonTexture; draw.ribbonTexture, shared/effect_draw.h): u runs
// along the line, growing from the head towards the tail, v across it. Each vertex gets u by the
// texture's mode: stretch, the sample's age over the live ribbon's age span (once from the head to
// the oldest sample); per segment, tau (once over each frame's segment); tiled, the age times
// repeats / lifetime (the pattern rides with the head); distance, the sample's distance from where
// its line began (render/kinds/speed_lines_pass.h, ribbon_distance.comp) over the tile length,
// negated (fixed on the path as it is drawn). The fragment then samples the texture (repeating),
// scrolled by the offset of the moment, and erodes it: a texel is kept while its alpha stands above
// the threshold at its life, e = erosion_over_life(life) * (1 + s), faded over the soft edge s:
// smoothstep(e - s, e, alpha) (0: nothing eaten; 1: everything).
#ifndef MFX_RIBBON_TEXTURE_GLSL
#define MFX_RIBBON_TEXTURE_GLSL

#include "effect_common.glsl"
#include "ribbon_style.glsl"

// u at a vertex whose sample was taken at `sampleTime`, `tau` along its segment, `distance` along
// its line.
float ribbonU(float sampleTime, float tau, float distance) {
    float mode = draw.ribbonTexture.x;
    if (mode > 3.5) return -distance * draw.ribbonTexture.y;
    if (mode > 1.5 && mode < 2.5) return tau;
    return max(draw.timing.x - sampleTime, 0.0) * draw.ribbonTexture.y; // stretch, tiled
}

// The texel at `uv` (v 0..1 across) scrolled as the moment asks; `size` the texture's size.
vec2 ribbonTexel(vec2 uv, vec2 size) {
    vec2 half_ = 0.5 / size;
    float u = uv.x + draw.ribbonTexture.z;
    // Stretch and per segment map the texture once: clamped half a texel in from its ends, so the
    // repeating sampler does not blend the first column into the last (wrapped when scrolling).
    if (draw.ribbonTexture.x < 2.5)
        u = clamp(draw.ribbonTexture.z == 0.0 ? u : fract(u), half_.x, 1.0 - half_.x);
    return vec2(u, clamp(uv.y, half_.y, 1.0 - half_.y));
}

// The colour (RGBA, straight alpha) `colour` textured and eroded at `uv`, life `life`.
vec4 textured(vec4 colour, vec2 uv, float life, sampler2D tex) {
    if (draw.ribbonTexture.x < 0.5) return colour;
    vec4 t = texture(tex, ribbonTexel(uv, vec2(textureSize(tex, 0))));
    colour *= t;
    float soft = draw.ribbonTexture.w;
    if (soft > 0.0) {
        float e = erosionOverLife(life) * (1.0 + soft);
        colour.a *= smoothstep(e - soft, e, t.a);
    }
    return colour;
}

#endif
