// vorticityConfinement, third pass: each face not on a wall gains dt times the mean confinement
// force (shaders/confinement_force.comp) of the two cells beside it (docs/fluid.md; Fedkiw, Stam,
// Jensen 2001, eq. 11). Twin: fluid/reference/vorticity_confinement.cpp. One dispatch per
// component, writing every face of it (unchanged on walls) to a buffer that the solver copies
// into the component's image.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityX;
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityY;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityZ;
layout(binding = 4, rgba32f) uniform readonly image3D force;
layout(std430, binding = 5) writeonly buffer Out {
    float outValues[];
};

void main() {
    int c = int(kTarget);
    ivec3 q = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(q, faceCount(c)))) return;
    float value = c == 0 ? imageLoad(velocityX, q).r
                         : (c == 1 ? imageLoad(velocityY, q).r : imageLoad(velocityZ, q).r);
    if (!wallNormalFace(c, q)) {
        ivec3 below = q;
        below[c] -= 1;
        float f = 0.5 * (imageLoad(force, resolveCell(below))[c] + imageLoad(force, resolveCell(q))[c]);
        value += timeStep() * f;
    }
    outValues[faceElement(c, q)] = value;
}
