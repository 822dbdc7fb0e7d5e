// silhouetteShellUpdate: one update of the silhouette of motion, one invocation per bound polygon
// (Jones 2004, Sec. 3.2.4). Updates fall `1 / updatesPerFrame` of a frame apart; the vertices at an
// update lie on the straight line from their last frame's position to this frame's.
//   facing:     a vertex faces the motion when its normal . (now - at the previous update) > 0,
//               away when < 0; a vertex that has not moved faces neither way;
//   silhouette: a polygon with one vertex on one side and two on the other (the edge rule picks
//               which side) has the edge between those two on the silhouette: it records their
//               positions and normals in the slot of this update, remembers their indices and
//               sets its count of updates since to 0;
//   otherwise:  the count grows by one and the slot takes the last edge's vertices where they are
//               now, so a polygon off the silhouette for a few updates leaves no hole (Sec. 3.3).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "silhouette_shell_common.glsl"

layout(local_size_x = MFX_SHELL_GROUP_SIZE) in;

float updateFraction(uint update) {
    return float(update) / float(constants.updatesPerFrame);
}

vec3 positionAt(uint v, float f) {
    return mix(last[v].position.xyz, current[v].position.xyz, f);
}

vec3 normalAt(uint v, float f) {
    vec3 n = mix(last[v].normal.xyz, current[v].normal.xyz, f);
    return dot(n, n) > 0.0 ? normalize(n) : current[v].normal.xyz;
}

// +1 facing the motion since the previous update, -1 facing away, 0 still.
int facing(uint v, float f, float previous) {
    vec3 motion = positionAt(v, f) - positionAt(v, previous);
    if (length(motion) <= MFX_SHELL_STILL) return 0;
    float d = dot(normalAt(v, f), motion);
    return d > 0.0 ? 1 : d < 0.0 ? -1 : 0;
}

void main() {
    uint t = gl_GlobalInvocationID.x;
    if (t >= constants.triangleCount) return;
    float f = updateFraction(constants.update + 1u), previous = updateFraction(constants.update);
    uint v[3] = uint[3](triangles[3u * t], triangles[3u * t + 1u], triangles[3u * t + 2u]);
    int side[3] = int[3](facing(v[0], f, previous), facing(v[1], f, previous),
                         facing(v[2], f, previous));
    // The lone vertex's side and the pair's, by the edge rule (Sec. 3.2.4: either is valid as long
    // as one is used throughout).
    int pairSide = constants.edgeRule == MFX_SHELL_EDGE_BACK ? -1 : 1;
    int lone = -1, pairCount = 0, loneCount = 0;
    for (int c = 0; c < 3; ++c) {
        if (side[c] == pairSide) ++pairCount;
        if (side[c] == -pairSide) {
            ++loneCount;
            lone = c;
        }
    }
    ShellTriangleState state = states[t];
    uint slot = constants.newest * constants.triangleCount + t;
    bool latest = constants.update + 1u == constants.updatesPerFrame;
    if (pairCount == 2 && loneCount == 1) {
        // The pair in the polygon's winding, so the strip keeps one orientation.
        state.edgeA = v[(lone + 1) % 3];
        state.edgeB = v[(lone + 2) % 3];
        state.sinceSilhouette = 0u;
        state.hasEdge = 1u;
        if (latest) atomicAdd(counters.silhouetteTriangles, 1u);
    } else if (state.hasEdge != 0u) {
        state.sinceSilhouette = min(state.sinceSilhouette + 1u, 1000000u);
    }
    ShellHistoryEdge edge;
    if (state.hasEdge != 0u) {
        uint status = state.sinceSilhouette == 0u ? MFX_SHELL_SLOT_EDGE : MFX_SHELL_SLOT_LAST_EDGE;
        edge.positionA = vec4(positionAt(state.edgeA, f), float(status));
        edge.positionB = vec4(positionAt(state.edgeB, f), 1.0);
        edge.normalA = vec4(normalAt(state.edgeA, f), 0.0);
        edge.normalB = vec4(normalAt(state.edgeB, f), 0.0);
    } else {
        edge.positionA = vec4(0.0, 0.0, 0.0, float(MFX_SHELL_SLOT_EMPTY));
        edge.positionB = vec4(0.0);
        edge.normalA = vec4(0.0);
        edge.normalB = vec4(0.0);
    }
    history[slot] = edge;
    states[t] = state;
}
