// sweptVolumeBuild: the translucent part of the motion volume (Wloka and Zeleznik 1996, Sec. 3.2,
// 3.3 and 4.2), one invocation per interior edge and then one per triangle of the bound part:
//   split:    a triangle is on the front if its normal . motion >= 0, else on the back (Sec. 3.2);
//   contour:  an edge between a front and a back triangle, kept when one of the two faces the
//             camera (the contour-line, Sec. 3.2);
//   joining:  each contour-line edge swept back through the recorded positions of its two
//             vertices, `pieces` quads per segment, alpha falling from opaque at now to the
//             trailing value (Sec. 3.3, 3.4; 4.2 for n segments); the lighting normal and colour
//             those of the leading edge (Sec. 4.1, footnote 1);
//   trailing: each camera-facing back triangle at its vertices' oldest positions, with the
//             trailing alpha (Sec. 3.3; Sec. 4.3: the part's orientation then, not now).
// The leading side, the front at now, is the part itself, drawn opaque by the scene pass.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "swept_volume_common.glsl"

layout(local_size_x = MFX_SWEPT_GROUP_SIZE) in;

vec3 triangleNormal(uint t) {
    return normalize(skinned[triangles[3u * t]].normal.xyz +
                     skinned[triangles[3u * t + 1u]].normal.xyz +
                     skinned[triangles[3u * t + 2u]].normal.xyz + vec3(1e-20));
}

vec3 triangleCentre(uint t) {
    return (skinned[triangles[3u * t]].position.xyz + skinned[triangles[3u * t + 1u]].position.xyz +
            skinned[triangles[3u * t + 2u]].position.xyz) /
           3.0;
}

bool facesMotion(uint t, vec3 motion) {
    return dot(triangleNormal(t), motion) >= 0.0;
}

bool facesCamera(uint t) {
    return dot(triangleNormal(t), constants.cameraPosition.xyz - triangleCentre(t)) > 0.0;
}

void emit(uint at, uint vertex, vec3 position, float s) {
    TrajectoryVertex v;
    v.position = vec4(position, s);                // w: the place along the sweep, 0 now
    v.normal = vec4(skinned[vertex].normal.xyz, 0.0); // w: sample time 0: no age fade
    vec4 colour = colours[vertex];
    v.color = vec4(colour.rgb, colour.a * sweptAlpha(s));
    v.velocity = vec4(0.0);
    outputVertices[at] = v;
}

void joinContourEdge(uint k, vec3 motion, uint segments) {
    uint ta = edges[6u * k], tb = edges[6u * k + 1u];
    bool frontA = facesMotion(ta, motion), frontB = facesMotion(tb, motion);
    if (frontA == frontB) return;
    if (!facesCamera(ta) && !facesCamera(tb)) return;
    uint leading = frontA ? 0u : 1u;
    uint a = edges[6u * k + 2u + 2u * leading], b = edges[6u * k + 3u + 2u * leading];
    atomicAdd(counters.contourEdges, 1u);
    uint quads = segments * constants.pieces;
    uint base = atomicAdd(counters.vertexCount, 6u * quads);
    vec3 a0 = pathAt(a, 0.0), b0 = pathAt(b, 0.0);
    for (uint q = 0u; q < quads; ++q) {
        float s0 = float(q) / float(quads), s1 = float(q + 1u) / float(quads);
        vec3 a1 = pathAt(a, s1 * float(segments)), b1 = pathAt(b, s1 * float(segments));
        uint at = base + 6u * q;
        emit(at, a, a0, s0);
        emit(at + 1u, b, b0, s0);
        emit(at + 2u, b, b1, s1);
        emit(at + 3u, a, a0, s0);
        emit(at + 4u, b, b1, s1);
        emit(at + 5u, a, a1, s1);
        a0 = a1;
        b0 = b1;
    }
}

void drawTrailing(uint t, vec3 motion, uint segments) {
    if (facesMotion(t, motion) || !facesCamera(t)) return;
    atomicAdd(counters.trailingTriangles, 1u);
    uint base = atomicAdd(counters.vertexCount, 3u);
    for (uint c = 0u; c < 3u; ++c) {
        uint vertex = triangles[3u * t + c];
        emit(base + c, vertex, recorded(vertex, segments), 1.0);
    }
}

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= constants.edgeCount + constants.triangleCount) return;
    uint segments = sweptSegments();
    vec3 motion = counters.motion.xyz;
    if (segments == 0u || length(motion) <= MFX_SWEPT_STILL) return; // still: no volume
    if (k < constants.edgeCount)
        joinContourEdge(k, motion, segments);
    else
        drawTrailing(k - constants.edgeCount, motion, segments);
}
