// vorticityConfinement, third pass: each face not on a wall gains dt times the mean confinement
// force (shaders/fluid/confinement_force.comp) of the two cells beside it (docs/fluid.md; Fedkiw, Stam,
// Jensen 2001, eq. 11). Twin: fluid/reference/vorticity_confinement.cpp. One dispatch over the
// largest face extent (cells + 1 along each axis): invocation q writes face q of each component
// that has one (unchanged on walls) to that component's buffer, which the solver copies into the
// component's image, or with kDirectStore into the image itself. The force of cell q serves all
// three faces, so each invocation loads four force texels instead of six.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#include "fluid_solids.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityX;
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityY;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform readonly image3D velocityZ;
layout(binding = 4, rgba32f) uniform readonly image3D force;
layout(std430, binding = 5) writeonly buffer OutX {
    float outX[];
};
layout(std430, binding = 6) writeonly buffer OutY {
    float outY[];
};
layout(std430, binding = 7) writeonly buffer OutZ {
    float outZ[];
};
// kDirectStore: the faces straight into the live velocity images (each invocation reads only the
// faces it writes).
layout(binding = 8, MFX_VELOCITY_FORMAT) uniform writeonly image3D outImageX;
layout(binding = 9, MFX_VELOCITY_FORMAT) uniform writeonly image3D outImageY;
layout(binding = 10, MFX_VELOCITY_FORMAT) uniform writeonly image3D outImageZ;

float velocity(int c, ivec3 q) {
    return c == 0 ? imageLoad(velocityX, q).r
                  : (c == 1 ? imageLoad(velocityY, q).r : imageLoad(velocityZ, q).r);
}

// Face q of component c with the force of the cells on either side: `here` (cell q) and `below`
// (cell q - e_c), both already resolved.
float forcedFace(int c, ivec3 q, vec4 here, vec4 below) {
    float value = velocity(c, q);
    // Solid faces keep the solid's velocity.
    if (!wallNormalFace(c, q) && !(solidsNearWorkgroup() && solidFace(c, q))) value += timeStep() * (0.5 * (below[c] + here[c]));
    return value;
}

void main() {
    ivec3 q = stageInvocation();
    if (any(greaterThan(q, cellCount()))) return;
    vec4 here = imageLoad(force, resolveCell(q));
    if (all(lessThan(q, faceCount(0)))) {
        float v = forcedFace(0, q, here, imageLoad(force, resolveCell(q - ivec3(1, 0, 0))));
        if (kDirectStore)
            imageStore(outImageX, q, vec4(MFX_STORED(v)));
        else
            outX[faceElement(0, q)] = v;
    }
    if (all(lessThan(q, faceCount(1)))) {
        float v = forcedFace(1, q, here, imageLoad(force, resolveCell(q - ivec3(0, 1, 0))));
        if (kDirectStore)
            imageStore(outImageY, q, vec4(MFX_STORED(v)));
        else
            outY[faceElement(1, q)] = v;
    }
    if (all(lessThan(q, faceCount(2)))) {
        float v = forcedFace(2, q, here, imageLoad(force, resolveCell(q - ivec3(0, 0, 1))));
        if (kDirectStore)
            imageStore(outImageZ, q, vec4(MFX_STORED(v)));
        else
            outZ[faceElement(2, q)] = v;
    }
}
