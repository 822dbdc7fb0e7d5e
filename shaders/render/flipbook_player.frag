// flipbookPlayer: a flipbook sheet baked by `motionfx bake` (docs/flipbook.md) played on a quad,
// each picture blended from the two cells around the playhead with the motion vectors of the
// first (render/flipbook.h, whose blendCells is this shader's CPU twin):
//     out(uv) = (1 - t) A(uv - t m(uv)) + t B(uv + (1 - t) m(uv)),
// m = A's motion, decoded from the motion sheet's rg as (2 rg - 1) scale. Without motion (scale 0)
// it is a plain cross-fade. Both sheets are read as stored (UNORM views): the colour is
// premultiplied, to be blended with (one, one minus source alpha). Each cell is filtered
// bilinearly by hand with texelFetch, transparent outside the cell, so no neighbouring cell bleeds
// in at its edge (the bake's margin keeps the effect away from the edges anyway; an engine may as
// well use its sampler's bilinear filtering).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "shared/flipbook.h"

layout(push_constant) uniform Play {
    FlipbookPlay play;
};
layout(binding = 0) uniform sampler2D colourSheet;
layout(binding = 1) uniform sampler2D motionSheet;

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 outColour;

vec4 cellTexel(sampler2D sheet, ivec2 origin, ivec2 size, ivec2 p) {
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) return vec4(0.0);
    return texelFetch(sheet, origin + p, 0);
}

// Cell `cell` of `sheet` at the cell's uv, filtered bilinearly (pixel centres at +0.5).
vec4 sampleCell(sampler2D sheet, int cell, vec2 cellUv) {
    ivec2 grid = ivec2(play.grid.xy);
    ivec2 size = textureSize(sheet, 0) / grid;
    ivec2 origin = ivec2(cell % grid.x, cell / grid.x) * size;
    vec2 p = cellUv * vec2(size) - 0.5;
    vec2 f = floor(p);
    vec2 a = p - f;
    ivec2 i = ivec2(f);
    vec4 top = mix(cellTexel(sheet, origin, size, i), cellTexel(sheet, origin, size, i + ivec2(1, 0)),
                   a.x);
    vec4 bottom = mix(cellTexel(sheet, origin, size, i + ivec2(0, 1)),
                      cellTexel(sheet, origin, size, i + ivec2(1, 1)), a.x);
    return mix(top, bottom, a.y);
}

void main() {
    int cells = int(play.grid.z);
    bool loop = play.playhead.y > 0.5;
    float position = loop ? mod(play.playhead.x, float(cells))
                          : clamp(play.playhead.x, 0.0, float(cells - 1));
    int a = min(int(floor(position)), cells - 1);
    float t = position - float(a);
    int b = a + 1;
    if (b == cells) {
        b = loop ? 0 : a;
        if (!loop) t = 0.0;
    }
    vec2 m = vec2(0.0);
    if (play.grid.w > 0.0) m = (sampleCell(motionSheet, a, uv).rg * 2.0 - 1.0) * play.grid.w;
    vec4 from = sampleCell(colourSheet, a, uv - t * m);
    vec4 to = sampleCell(colourSheet, b, uv + (1.0 - t) * m);
    outColour = mix(from, to, t);
}
