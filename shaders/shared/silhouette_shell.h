// Structures of the silhouette-of-motion blur shell (render/kinds/silhouette_shell_pass.h;
// shaders/silhouette_shell_*.comp), shared by GLSL and C++. Jones 2004, "Geometric Motion Blur for
// Deforming Polygonal Models": Sec. 3.2.3 (per-polygon data), 3.2.4 (finding the silhouette of
// motion), 3.2.5 (the polygon strips), 3.3 (holes and popping).
#ifndef MFX_SHARED_SILHOUETTE_SHELL_H
#define MFX_SHARED_SILHOUETTE_SHELL_H

#include "common.h"

#define MFX_SHELL_GROUP_SIZE 64
// Subdivisions of the shell: silhouettes kept per polygon (Sec. 3.2.2). The ring holds one more,
// the silhouette of the latest update, which is where the live mesh is.
#define MFX_SHELL_MAX_SUBDIVISIONS 32
// Updates of the silhouette per scene frame at most (Sec. 3.2.2: blur time / subdivisions apart).
#define MFX_SHELL_MAX_UPDATES_PER_FRAME 8

// Which edge of a polygon lies on the silhouette of motion (Sec. 3.2.4; scene::ShellEdgeRule):
// the edge between its two back-facing vertices when the third faces the motion (the paper's
// choice, Figure 10), or between its two front-facing vertices when the third faces away.
#define MFX_SHELL_EDGE_BACK 0u
#define MFX_SHELL_EDGE_FRONT 1u

// What a slot of a polygon's ring holds (HistoryEdge.positionA.w).
#define MFX_SHELL_SLOT_EMPTY 0u     // nothing recorded since the shell started
#define MFX_SHELL_SLOT_EDGE 1u      // the polygon's edge on that update's silhouette
#define MFX_SHELL_SLOT_LAST_EDGE 2u // off the silhouette: its last edge, where it was (Sec. 3.3)

// Below this motion between updates (world units) a vertex counts as still and faces neither way:
// a part that does not move has no silhouette of motion (Sec. 3.2.4).
#define MFX_SHELL_STILL 1e-7

MFX_SHARED_BEGIN

// Push constants of every silhouette_shell stage.
struct SilhouetteShellConstants {
    uint vertexCount;     // bound vertices
    uint triangleCount;   // bound triangles
    uint historySlots;    // subdivisions + 1
    uint subdivisions;    // S: a full strip has S quads, its last pair transparent (Sec. 3.2.5)
    uint newest;          // the slot this update writes (the update index, Sec. 3.2.3)
    uint update;          // u of updatesPerFrame: this update lies at (u + 1) / updatesPerFrame
    uint updatesPerFrame; // silhouette updates between two recorded frames
    uint edgeRule;        // MFX_SHELL_EDGE_*
    float initialAlpha;   // alpha of the strip at the live mesh
    uint fadeOut;         // updates a polygon off the silhouette keeps fading its strip
    uint pad0;
    uint pad1;
};

// The state of one polygon (Sec. 3.2.3): the indices of the last two of its vertices on the
// silhouette, the updates since, and whether it has had an edge since the shell started.
struct ShellTriangleState {
    uint edgeA;
    uint edgeB;
    uint sinceSilhouette;
    uint hasEdge;
};

// One slot of a polygon's ring: an edge's two positions and normals (w of positionA:
// MFX_SHELL_SLOT_*).
struct ShellHistoryEdge {
    vec4 positionA;
    vec4 positionB;
    vec4 normalA;
    vec4 normalB;
};

// A vertex between updates: its position and averaged normal (Sec. 3.2.2).
struct ShellVertex {
    vec4 position;
    vec4 normal;
};

// Written by the passes each frame, read as indirect draw arguments and by the CPU.
struct SilhouetteShellCounters {
    uint vertexCount; // VkDrawIndirectCommand of the strips' triangles
    uint instanceCount;
    uint firstVertex;
    uint firstInstance;
    uint silhouetteTriangles; // polygons with an edge on the latest update's silhouette
    uint strips;              // strips drawn
    uint fadingStrips;        // of them, polygons off the silhouette fading out (Sec. 3.3)
    uint pad0;
};

MFX_SHARED_END

#ifdef __cplusplus
MFX_CHECK_SIZE(SilhouetteShellConstants, 48);
MFX_CHECK_LAYOUT(SilhouetteShellConstants, initialAlpha, 32);
MFX_CHECK_SIZE(ShellTriangleState, 16);
MFX_CHECK_SIZE(ShellHistoryEdge, 64);
MFX_CHECK_SIZE(ShellVertex, 32);
MFX_CHECK_SIZE(SilhouetteShellCounters, 32);
MFX_CHECK_LAYOUT(SilhouetteShellCounters, silhouetteTriangles, 16);
#endif

#endif
