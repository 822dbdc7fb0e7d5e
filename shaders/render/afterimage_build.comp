// afterimageBuild: the geometry drawn this frame, per primitive of the bound mesh part.
//   smear: the triangles with at least one pushed vertex (Smith 2016, Sec. 5.4 suggests choosing
//          the triangles each update); the others coincide with the character and are not drawn;
//   multi: for each edge with a pushed end, quads between its "frame vertices" j and j + 1
//          (Sec. 5.1.2), frame vertex j of a pushed vertex lying j * R * taper * I frames back
//          along its recorded path (the arc through the afterimages), I the influence
//          (1 - (1 - D_i/Dmax) j/n)^k (Sec. 5.3, function b); an unpushed end stays on the mesh.
// Alpha falls along the arc with j / n.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "afterimage_common.glsl"

layout(local_size_x = MFX_AFTERIMAGE_GROUP_SIZE) in;

// Where a frame vertex is: `back` frames back along the recorded path, between ring slots.
vec3 pathAt(uint vertex, float back) {
    back = clamp(back, 0.0, float(constants.filled - 1u));
    uint b0 = uint(floor(back));
    uint b1 = min(b0 + 1u, constants.filled - 1u);
    return mix(recorded(vertex, b0), recorded(vertex, b1), back - float(b0));
}

vec3 frameVertex(uint vertex, uint j, uint images, float longest) {
    TrajectoryVertex v = pushed[vertex];
    if (v.position.w == 0.0) return v.position.xyz;
    float influence = 1.0;
    if (constants.influencePower > 0.0 && longest > 0.0) {
        float relative = clamp(pathLength(vertex) / longest, 0.0, 1.0);
        influence = pow(1.0 - (1.0 - relative) * float(j) / float(images), constants.influencePower);
    }
    return pathAt(vertex, float(j) * v.velocity.w * influence);
}

void emit(uint at, uint vertex, vec3 position, float s) {
    TrajectoryVertex v;
    v.position = vec4(position, s);
    v.normal = vec4(pushed[vertex].normal.xyz, 0.0);
    vec4 colour = colours[vertex];
    v.color = vec4(colour.rgb, colour.a * alphaAt(s));
    v.velocity = vec4(0.0);
    outputVertices[at] = v;
}

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= constants.primitiveCount) return;
    if (constants.variant == MFX_AFTERIMAGE_SMEAR) {
        uint a = primitives[3u * k], b = primitives[3u * k + 1u], c = primitives[3u * k + 2u];
        if (pushed[a].position.w + pushed[b].position.w + pushed[c].position.w == 0.0) return;
        uint base = atomicAdd(counters.indexCount, 3u);
        drawnIndices[base] = a;
        drawnIndices[base + 1u] = b;
        drawnIndices[base + 2u] = c;
        return;
    }
    uint a = primitives[2u * k], b = primitives[2u * k + 1u];
    if (pushed[a].position.w == 0.0 && pushed[b].position.w == 0.0) return;
    uint images = arcImages();
    if (images == 0u) return;
    float longest = uintBitsToFloat(counters.longestBits);
    uint base = atomicAdd(counters.vertexCount, 6u * images);
    vec3 a0 = frameVertex(a, 0u, images, longest), b0 = frameVertex(b, 0u, images, longest);
    for (uint j = 0u; j < images; ++j) {
        vec3 a1 = frameVertex(a, j + 1u, images, longest);
        vec3 b1 = frameVertex(b, j + 1u, images, longest);
        float s0 = float(j) / float(images), s1 = float(j + 1u) / float(images);
        uint at = base + 6u * j;
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
