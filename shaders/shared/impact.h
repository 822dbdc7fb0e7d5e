// The impact effect's GPU data (render/kinds/impact_pass.h; shaders/render/impact_*): the sparks a
// hit throws, their streaks at the frame's time, and the draws of sparks, flash and ring.
#ifndef MFX_SHARED_IMPACT_H
#define MFX_SHARED_IMPACT_H

#include "common.h"

MFX_SHARED_BEGIN

// One spark as a hit throws it (written by the host when the hit happens).
struct ImpactSpark {
    vec4 origin;   // xyz: where it starts (the contact point, world); w: the hit's scene time (s)
    vec4 velocity; // xyz: its velocity at the hit (m/s); w: its life (s)
};

// A spark's streak at the frame's time (impact_sparks.comp): from its position `stretch` seconds
// earlier (never before the hit) to its position now.
struct ImpactStreak {
    vec4 head; // xyz: position now; w: life u = age / life (drawn for u in [0, 1))
    vec4 tail; // xyz: position `stretch` seconds earlier; w: unused
};

// Push constants of impact_sparks.comp.
#define MFX_IMPACT_GROUP_SIZE 64
struct ImpactSparkConstants {
    vec4 motion; // x: the frame's scene time (s); y: gravity (m/s^2, along -y); z: linear drag
                 // (1/s); w: the streak's length in seconds of flight
    uint first;  // the first spark evaluated
    uint count;  // the sparks evaluated from it
    uint pad0, pad1;
};

// Push constants of the impact draws (impact.vert/.frag).
#define MFX_IMPACT_SPARKS 0.0
#define MFX_IMPACT_FLASH 1.0
#define MFX_IMPACT_RING 2.0
struct ImpactDraw {
    vec4 centre; // xyz: the flash's or ring's centre (world); w: MFX_IMPACT_*
    vec4 axisU;  // xyz: the quad's first half axis (world; zero: facing the camera); w: half size
    vec4 axisV;  // xyz: its second half axis; w: sparks: the streak's width (world units)
    vec4 colour; // rgb: linear colour times intensity; a: alpha
    vec4 ring;   // x, y: the ring's inner and outer radius as fractions of the half size;
                 // z: 1 = additive; w: depth fade (world units)
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(ImpactSpark, 32);
MFX_CHECK_SIZE(ImpactStreak, 32);
MFX_CHECK_SIZE(ImpactSparkConstants, 32);
MFX_CHECK_SIZE(ImpactDraw, 80);
MFX_CHECK_LAYOUT(ImpactDraw, ring, 64);
#endif

#endif
