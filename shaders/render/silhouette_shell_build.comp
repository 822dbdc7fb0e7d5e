// silhouetteShellBuild: the blur shell, one quad strip per polygon (Jones 2004, Sec. 3.2.5 and
// 3.3), one invocation per bound polygon:
//   live pair: the strip starts at the polygon's last silhouette edge where the mesh is now, so it
//              stays attached however the mesh moves between updates (Sec. 3.2.5, Figure 12);
//   history:   then one pair a past update, newest first, through the polygon's ring, stopping at
//              a slot recorded before the shell started; at most `subdivisions` quads;
//   alpha:     the initial value at the live pair, falling by initial / subdivisions a pair, so a
//              full strip ends transparent (Sec. 3.2.5);
//   fade-out:  a polygon off the silhouette for k updates scales its whole strip by
//              1 - k / (fadeOut + 1) and draws none after fadeOut updates, so strips never pop out
//              (Sec. 3.3).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "silhouette_shell_common.glsl"

layout(local_size_x = MFX_SHELL_GROUP_SIZE) in;

void emit(uint at, vec3 position, vec3 normal, vec4 colour, uint pair, float fade) {
    float place = float(pair) / float(constants.subdivisions);
    TrajectoryVertex v;
    v.position = vec4(position, place); // w: the place along the strip, 0 at the live mesh
    v.normal = vec4(normal, 0.0);        // w: sample time 0: no age fade (effect_common.glsl)
    float alpha = constants.initialAlpha * fade * max(1.0 - place, 0.0);
    v.color = vec4(colour.rgb, colour.a * alpha);
    v.velocity = vec4(0.0);
    outputVertices[at] = v;
}

void main() {
    uint t = gl_GlobalInvocationID.x;
    if (t >= constants.triangleCount) return;
    ShellTriangleState state = states[t];
    if (state.hasEdge == 0u || state.sinceSilhouette > constants.fadeOut) return;
    uint quads = 0u;
    while (quads < constants.subdivisions &&
           uint(recordedEdge(t, quads + 1u).positionA.w) != MFX_SHELL_SLOT_EMPTY)
        ++quads;
    if (quads == 0u) return;
    float fade = 1.0 - float(state.sinceSilhouette) / float(constants.fadeOut + 1u);
    atomicAdd(counters.strips, 1u);
    if (state.sinceSilhouette > 0u) atomicAdd(counters.fadingStrips, 1u);
    uint base = atomicAdd(counters.vertexCount, 6u * quads);

    vec4 colourA = colours[state.edgeA], colourB = colours[state.edgeB];
    vec3 a0 = skinned[state.edgeA].position.xyz, b0 = skinned[state.edgeB].position.xyz;
    vec3 na0 = current[state.edgeA].normal.xyz, nb0 = current[state.edgeB].normal.xyz;
    for (uint q = 0u; q < quads; ++q) {
        ShellHistoryEdge edge = recordedEdge(t, q + 1u);
        vec3 a1 = edge.positionA.xyz, b1 = edge.positionB.xyz;
        vec3 na1 = edge.normalA.xyz, nb1 = edge.normalB.xyz;
        uint at = base + 6u * q;
        emit(at, a0, na0, colourA, q, fade);
        emit(at + 1u, b0, nb0, colourB, q, fade);
        emit(at + 2u, b1, nb1, colourB, q + 1u, fade);
        emit(at + 3u, a0, na0, colourA, q, fade);
        emit(at + 4u, b1, nb1, colourB, q + 1u, fade);
        emit(at + 5u, a1, na1, colourA, q + 1u, fade);
        a0 = a1;
        b0 = b1;
        na0 = na1;
        nb0 = nb1;
    }
}
