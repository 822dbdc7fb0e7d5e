// What the silhouette-shell stages share (render/kinds/silhouette_shell_pass.h): one descriptor layout
// for the three stages and the ring of each polygon's past silhouette edges.
// Jones 2004, "Geometric Motion Blur for Deforming Polygonal Models", Sec. 3.2.
#ifndef MFX_SILHOUETTE_SHELL_COMMON_GLSL
#define MFX_SILHOUETTE_SHELL_COMMON_GLSL

#include "shared/silhouette_shell.h"
#include "shared/skinning.h"
#include "shared/trajectory.h"

layout(push_constant) uniform Constants {
    SilhouetteShellConstants constants;
};
// The bound vertices skinned for this frame.
layout(std430, binding = 0) readonly buffer Skinned {
    SkinVertexOut skinned[];
};
// The polygons around each vertex (its copies at seams included): vertexCount + 1 offsets, then
// the triangle lists they index.
layout(std430, binding = 1) readonly buffer Adjacency {
    uint adjacency[];
};
// Bound triangles, 3 vertex indices each.
layout(std430, binding = 2) readonly buffer Triangles {
    uint triangles[];
};
// This frame's positions and averaged normals, and the last frame's.
layout(std430, binding = 3) buffer Current {
    ShellVertex current[];
};
layout(std430, binding = 4) readonly buffer Last {
    ShellVertex last[];
};
layout(std430, binding = 5) buffer States {
    ShellTriangleState states[];
};
// Each polygon's ring of edges, slot-major: history[slot * triangleCount + triangle].
layout(std430, binding = 6) buffer History {
    ShellHistoryEdge history[];
};
layout(std430, binding = 7) readonly buffer Colours {
    vec4 colours[];
};
layout(std430, binding = 8) writeonly buffer Output {
    TrajectoryVertex outputVertices[];
};
layout(std430, binding = 9) buffer Counters {
    SilhouetteShellCounters counters;
};

// The slot `back` updates before the latest one (0: the latest).
uint slotBack(uint back) {
    return (constants.newest + constants.historySlots - back % constants.historySlots) %
           constants.historySlots;
}

ShellHistoryEdge recordedEdge(uint triangle, uint back) {
    return history[slotBack(back) * constants.triangleCount + triangle];
}

#endif
