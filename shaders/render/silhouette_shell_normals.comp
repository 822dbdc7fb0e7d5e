// silhouetteShellNormals: each bound vertex's position and averaged normal for this frame. The
// silhouette of motion is found from vertex normals, and the best results come from each normal
// being the average of its polygons' normals (Jones 2004, Sec. 3.2.2): a flat-shaded polygon,
// whose vertices all share its own normal, can never have an edge on the silhouette. So the normal
// is rebuilt here from the skinned polygons around the vertex, its copies at seams included
// (area-weighted: the cross product's length), whatever normals the mesh was authored with.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "silhouette_shell_common.glsl"

layout(local_size_x = MFX_SHELL_GROUP_SIZE) in;

void main() {
    uint v = gl_GlobalInvocationID.x;
    if (v >= constants.vertexCount) return;
    vec3 sum = vec3(0.0);
    for (uint k = adjacency[v]; k < adjacency[v + 1u]; ++k) {
        uint t = adjacency[k];
        vec3 p0 = skinned[triangles[3u * t]].position.xyz;
        vec3 p1 = skinned[triangles[3u * t + 1u]].position.xyz;
        vec3 p2 = skinned[triangles[3u * t + 2u]].position.xyz;
        sum += cross(p1 - p0, p2 - p0);
    }
    vec3 n = dot(sum, sum) > 0.0 ? normalize(sum) : skinned[v].normal.xyz;
    current[v].position = vec4(skinned[v].position.xyz, 1.0);
    current[v].normal = vec4(n, 0.0);
}
