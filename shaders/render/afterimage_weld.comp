// afterimageWeld: the copies of a seam vertex (one bind-pose position, several normals) move
// together (Smith 2016, Sec. 5.4: "if a vertex was determined to translate, all other vertices
// that share that location were translated as well"), or the smear tears away from the mesh where
// one copy faces away from its motion and another does not. Each vertex takes the push of the
// first of its copies that afterimage_smear.comp pushed back (in index order, so all copies agree),
// keeping its own normal and colour; a vertex none of whose copies was pushed stays as decided.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "afterimage_common.glsl"

layout(local_size_x = MFX_AFTERIMAGE_GROUP_SIZE) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= constants.vertexCount) return;
    TrajectoryVertex v = decided[i];
    for (uint k = copies[i]; k < copies[i + 1u]; ++k) {
        uint copy = copies[k];
        if (decided[copy].position.w == 0.0) continue;
        vec3 push = decided[copy].velocity.xyz;
        bool moved = constants.variant == MFX_AFTERIMAGE_SMEAR;
        v.position = vec4(skinned[i].position.xyz + (moved ? push : vec3(0.0)), 1.0);
        vec4 colour = colours[i];
        v.color = vec4(colour.rgb, colour.a * alphaAt(1.0));
        v.velocity = decided[copy].velocity;
        break;
    }
    pushed[i] = v;
    if (v.position.w != 0.0) atomicAdd(counters.pushedVertices, 1u);
}
