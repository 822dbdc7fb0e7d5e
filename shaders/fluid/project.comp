// project: u -= (p_high - p_low) / h on every face not on a wall; p = 0 across open faces, wrapped
// across periodic ones (docs/fluid.md). Twin: fluid/reference/project.cpp. One dispatch per
// component, writing every face of it (unchanged on walls) to a buffer that the solver copies
// into the component's image, or straight into the image (kDirectStore).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "fluid_common.glsl"
#include "fluid_solids.glsl"

// The component kTarget alone: the three dispatches then touch disjoint images, so they need no
// barrier between them on either store path.
layout(binding = 1, MFX_VELOCITY_FORMAT) uniform readonly image3D velocity;
layout(binding = 4, MFX_PRESSURE_FORMAT) uniform readonly image3D pressure;
layout(std430, binding = 5) writeonly buffer Out {
    float outValues[];
};
// kDirectStore: straight into the live component (each invocation reads only the face it writes).
layout(binding = 6, MFX_VELOCITY_FORMAT) uniform writeonly image3D outField;

float pressureAt(ivec3 q, int axis) {
    int n = cellCount()[axis];
    if (q[axis] >= 0 && q[axis] < n) return imageLoad(pressure, q).r;
    if (periodicAxis(axis)) {
        q[axis] = wrapIndex(q[axis], n);
        return imageLoad(pressure, q).r;
    }
    return 0.0;
}

void main() {
    int c = int(kTarget);
    ivec3 q = stageInvocation();
    if (any(greaterThanEqual(q, faceCount(c)))) return;
    float value = imageLoad(velocity, q).r;
    // u·n = u_solid·n kept on solid faces.
    if (!wallNormalFace(c, q) && !(solidsNearWorkgroup() && solidFace(c, q))) {
        ivec3 below = q;
        below[c] -= 1;
        float gradient = (pressureAt(q, c) - pressureAt(below, c)) * inverseCellSize();
        value -= gradient;
    }
    if (kDirectStore)
        imageStore(outField, q, vec4(MFX_STORED(value)));
    else
        outValues[faceElement(c, q)] = value;
}
