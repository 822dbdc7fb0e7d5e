// Structures of the afterimage toon blur (render/kinds/afterimage_pass.h;
// shaders/afterimage_*.comp), shared by GLSL and C++. Smith 2016, "Afterimage Toon Blur", chapters
// 4 (single afterimage) and 5 (multi-afterimage).
#ifndef MFX_SHARED_AFTERIMAGE_H
#define MFX_SHARED_AFTERIMAGE_H

#include "common.h"

#define MFX_AFTERIMAGE_GROUP_SIZE 64
// Recorded positions a multi-afterimage arc may run through (the ring holds one more: now).
#define MFX_AFTERIMAGE_MAX_IMAGES 16

// What is drawn (scene::AfterimageVariant).
#define MFX_AFTERIMAGE_SMEAR 0u
#define MFX_AFTERIMAGE_SPEED_LINES 1u
#define MFX_AFTERIMAGE_MULTI 2u

// Below this motion per frame (world units) a vertex counts as still: the same pose twice gives
// exactly zero, float noise in a re-skinned pose stays far below it.
#define MFX_AFTERIMAGE_STILL 1e-6

MFX_SHARED_BEGIN

// Push constants of afterimage_record, afterimage_smear and afterimage_build.
struct AfterimageConstants {
    vec4 characterMotion;    // xyz: the character's root travel this frame (world units), m^U
    uint vertexCount;        // bound vertices
    uint primitiveCount;     // afterimage_build: triangles (smear) or edges (multi)
    uint historySlots;       // positions per vertex in the ring
    uint newest;             // the slot holding this frame's position
    uint filled;             // slots holding a recorded position, 1..historySlots
    uint reset;              // 1: every slot takes this frame's position (no motion yet)
    uint variant;            // MFX_AFTERIMAGE_*
    uint afterimages;        // multi: recorded positions an arc runs through (n)
    float strengthCharacter; // f^U (Smith 2016, Sec. 4.3)
    float strengthAnimation; // f^V
    float randomMin;         // R in [randomMin, randomMax] ...
    float randomMax;
    float randomThreshold; // ... and 0 below this (Sec. 4.3 "R-Value Thresholding")
    float taper;           // push scaled by (-cos(normal, motion))^taper
    float minSpeed;        // world units per frame a vertex must move
    float relativeSpeed;   // fraction of the fastest bound vertex's motion it must reach
    float alphaStart;      // alpha at the live mesh ...
    float alphaEnd;        // ... and at the far end of the push or arc
    float alphaPower;      // alpha(s) = start + (end - start) s^power
    float influencePower;  // multi: k of the influence (Sec. 5.3, function b); 0: influence 1
    uint stride;           // speed lines: every n-th vertex
    uint pad0;
    uint pad1;
    uint pad2;
};

// Written by the passes each frame, read as indirect draw arguments and by the CPU.
struct AfterimageCounters {
    uint indexCount; // VkDrawIndexedIndirectCommand of the smeared mesh
    uint indexedInstanceCount;
    uint firstIndex;
    int vertexOffset;
    uint firstIndexedInstance;
    uint vertexCount; // VkDrawIndirectCommand of speed lines or arcs
    uint instanceCount;
    uint firstVertex;
    uint firstInstance;
    uint fastestBits;    // the fastest bound vertex's motion this frame (float bits, units/frame)
    uint longestBits;    // multi: the longest recorded path of a bound vertex (float bits), Dmax
    uint pushedVertices; // vertices pushed back this frame
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(AfterimageConstants, 112);
MFX_CHECK_LAYOUT(AfterimageConstants, vertexCount, 16);
MFX_CHECK_LAYOUT(AfterimageConstants, strengthCharacter, 48);
MFX_CHECK_LAYOUT(AfterimageConstants, influencePower, 92);
MFX_CHECK_LAYOUT(AfterimageConstants, stride, 96);
MFX_CHECK_SIZE(AfterimageCounters, 48);
MFX_CHECK_LAYOUT(AfterimageCounters, vertexCount, 20);
MFX_CHECK_LAYOUT(AfterimageCounters, fastestBits, 36);
#endif

#endif
