// applyBoundaries: wall-normal faces are 0; the top face of a periodic axis repeats face 0
// (docs/fluid.md). Twin: fluid/reference/apply_boundaries.cpp. One dispatch per component.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"

layout(binding = 1, MFX_VELOCITY_FORMAT) uniform image3D velocityX;
layout(binding = 2, MFX_VELOCITY_FORMAT) uniform image3D velocityY;
layout(binding = 3, MFX_VELOCITY_FORMAT) uniform image3D velocityZ;

void main() {
    int c = int(kTarget);
    // Dispatched over the two boundary layers of faces normal to c only: layer 0 is face 0,
    // layer 1 the top face n_c. Nothing else can be a wall-normal or periodic-top face.
    ivec3 q = ivec3(gl_GlobalInvocationID);
    ivec3 extent = faceCount(c);
    extent[c] = 2;
    if (any(greaterThanEqual(q, extent))) return;
    q[c] = q[c] == 0 ? 0 : cellCount()[c];
    bool wall = wallNormalFace(c, q);
    bool periodicTop = periodicAxis(c) && q[c] == cellCount()[c];
    if (!wall && !periodicTop) return;
    float value = 0.0;
    if (!wall) {
        ivec3 first = q;
        first[c] = 0;
        value = c == 0 ? imageLoad(velocityX, first).r
                       : (c == 1 ? imageLoad(velocityY, first).r : imageLoad(velocityZ, first).r);
    }
    if (c == 0)
        imageStore(velocityX, q, vec4(MFX_STORED(value)));
    else if (c == 1)
        imageStore(velocityY, q, vec4(MFX_STORED(value)));
    else
        imageStore(velocityZ, q, vec4(MFX_STORED(value)));
}
