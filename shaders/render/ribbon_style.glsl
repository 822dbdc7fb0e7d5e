// The speed-line ribbon's look over its life u = age / lifetime (0 at the head, 1 at the tail):
// colour_over_life, width_over_life and the texture's erosion_over_life, piecewise linear between their stops
// (scene::RibbonLook; core/scene/kinds/trail_effects.cpp colourAt and valueAt on the CPU).
// Every one of the MFX_RIBBON_MAX_STOPS stops is filled (the last given repeated at life 1), so
// the loops have a fixed length and no branch reads the uniform buffer: each step moves towards
// the next stop by how far u is past the previous one, which is 0 before it and 1 after it.
#ifndef MFX_RIBBON_STYLE_GLSL
#define MFX_RIBBON_STYLE_GLSL

#include "shared/effect_draw.h"

layout(std140, binding = 1) uniform Ribbon {
    RibbonStyle ribbon;
};

float colourStopAt(int i) {
    return ribbon.colourAt[i / 4][i % 4];
}
float widthStopAt(int i) {
    return ribbon.widthAt[i / 4][i % 4];
}
float widthOf(int i) {
    return ribbon.widths[i / 4][i % 4];
}

// How far u is from stop a to stop b, clamped to [0, 1] (1 when they coincide and u is past).
float between(float u, float a, float b) {
    return b > a ? clamp((u - a) / (b - a), 0.0, 1.0) : step(a, u);
}

vec4 colourOverLife(float u) {
    vec4 c = ribbon.colours[0];
    for (int i = 1; i < MFX_RIBBON_MAX_STOPS; ++i)
        c = mix(c, ribbon.colours[i], between(u, colourStopAt(i - 1), colourStopAt(i)));
    return c;
}

float erosionOverLife(float u) {
    float e = ribbon.erosion[0][0];
    for (int i = 1; i < MFX_RIBBON_MAX_STOPS; ++i)
        e = mix(e, ribbon.erosion[i / 4][i % 4],
                between(u, ribbon.erosionAt[(i - 1) / 4][(i - 1) % 4], ribbon.erosionAt[i / 4][i % 4]));
    return e;
}

float widthOverLife(float u) {
    float w = widthOf(0);
    for (int i = 1; i < MFX_RIBBON_MAX_STOPS; ++i)
        w = mix(w, widthOf(i), between(u, widthStopAt(i - 1), widthStopAt(i)));
    return w;
}

#endif
