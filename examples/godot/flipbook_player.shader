// A motionfx flipbook (`motionfx bake`, docs/flipbook.md) played on a CanvasItem (a Sprite,
// TextureRect or ColorRect) in Godot 3, blended between cells with the sheet's motion vectors:
//     out(uv) = (1 - t) A(uv - t m(uv)) + t B(uv + (1 - t) m(uv)),
// m = cell A's motion, decoded from the motion sheet's red and green as (2 rg - 1) motion_scale.
// With motion_scale 0 it is a plain cross-fade. The colour is premultiplied: blend_premul_alpha.
// Import both sheets without filtering, mipmaps or sRGB conversion (the shader filters each cell
// itself, so no neighbouring cell bleeds in at its edges). Set the uniforms from flipbook.json:
// grid (columns, rows), cells, motion_scale (motion_vectors.scale), and move `position` (in
// cells: cell index and fraction) at flipbook.json's fps.
shader_type canvas_item;
render_mode blend_premul_alpha;

uniform sampler2D colour_sheet;
uniform sampler2D motion_sheet;
uniform vec2 grid = vec2(8.0, 8.0);
uniform float cells = 64.0;
uniform float motion_scale = 0.0;
uniform float position = 0.0;
uniform bool loop = true;

vec4 cell_texel(sampler2D sheet, ivec2 origin, ivec2 size, ivec2 p) {
    if (p.x < 0 || p.y < 0 || p.x >= size.x || p.y >= size.y) {
        return vec4(0.0);
    }
    return texelFetch(sheet, origin + p, 0);
}

// Cell `cell` of `sheet` at the cell's uv, filtered bilinearly, transparent outside the cell.
vec4 sample_cell(sampler2D sheet, int cell, vec2 cell_uv) {
    ivec2 g = ivec2(grid);
    ivec2 size = textureSize(sheet, 0) / g;
    ivec2 origin = ivec2(cell % g.x, cell / g.x) * size;
    vec2 p = cell_uv * vec2(size) - 0.5;
    vec2 f = floor(p);
    vec2 a = p - f;
    ivec2 i = ivec2(f);
    vec4 top = mix(cell_texel(sheet, origin, size, i), cell_texel(sheet, origin, size, i + ivec2(1, 0)), a.x);
    vec4 bottom = mix(cell_texel(sheet, origin, size, i + ivec2(0, 1)), cell_texel(sheet, origin, size, i + ivec2(1, 1)), a.x);
    return mix(top, bottom, a.y);
}

void fragment() {
    int count = int(cells);
    float at = loop ? mod(position, cells) : clamp(position, 0.0, cells - 1.0);
    int a = min(int(floor(at)), count - 1);
    float t = at - float(a);
    int b = a + 1;
    if (b == count) {
        b = loop ? 0 : a;
        if (!loop) {
            t = 0.0;
        }
    }
    vec2 m = vec2(0.0);
    if (motion_scale > 0.0) {
        m = (sample_cell(motion_sheet, a, UV).rg * 2.0 - 1.0) * motion_scale;
    }
    vec4 from = sample_cell(colour_sheet, a, UV - t * m);
    vec4 to = sample_cell(colour_sheet, b, UV + (1.0 - t) * m);
    COLOR = mix(from, to, t);
}
