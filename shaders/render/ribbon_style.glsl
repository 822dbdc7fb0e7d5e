// The speed-line ribbon's look over its life u = age / lifetime (0 at the head, 1 at the tail):
// colour_over_life and width_over_life, piecewise linear between their stops
// (scene::RibbonLook; core/scene/kinds/trail_effects.cpp colourAt and valueAt on the CPU).
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

vec4 colourOverLife(float u) {
    int n = int(ribbon.counts.x);
    if (u <= colourStopAt(0)) return ribbon.colours[0];
    for (int i = 1; i < n; ++i)
        if (u <= colourStopAt(i)) {
            float span = colourStopAt(i) - colourStopAt(i - 1);
            float f = span > 0.0 ? (u - colourStopAt(i - 1)) / span : 1.0;
            return mix(ribbon.colours[i - 1], ribbon.colours[i], f);
        }
    return ribbon.colours[n - 1];
}

float widthOverLife(float u) {
    int n = int(ribbon.counts.y);
    if (u <= widthStopAt(0)) return ribbon.widths[0][0];
    for (int i = 1; i < n; ++i)
        if (u <= widthStopAt(i)) {
            float span = widthStopAt(i) - widthStopAt(i - 1);
            float f = span > 0.0 ? (u - widthStopAt(i - 1)) / span : 1.0;
            return mix(ribbon.widths[(i - 1) / 4][(i - 1) % 4], ribbon.widths[i / 4][i % 4], f);
        }
    return ribbon.widths[(n - 1) / 4][(n - 1) % 4];
}

#endif
